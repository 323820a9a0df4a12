#pragma once
// A number printed with a printf format, for the sim layer's error messages ("use a smaller dt
// (now 0.001 s)"). One definition shared by the files that build such messages, so that unity
// batches, which put several of them into one translation unit, see it once.

#include <cstdio>
#include <string>

namespace tumble {

inline std::string fmt(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace tumble
