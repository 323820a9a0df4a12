#pragma once
// `tumble --version`: "tumble X.Y.Z" on the first line (scripts and help2man read it), then one
// line "NAME VERSION" per library tumble runs with, collected from the layers that own them.

#include <string>

namespace tumble::cli {

std::string version_text();

}  // namespace tumble::cli
