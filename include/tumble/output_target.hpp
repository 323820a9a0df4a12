#pragma once
/// What an output path names, and how a finished output gets there — ffmpeg's rules, so that
/// `--diff-out /dev/null` discards and `/dev/stdout` streams:
/// - a regular file, or nothing yet, is *replaced*: the finished bytes are renamed over it in one
///   step (a reader sees the old file or the new one, never a mix);
/// - a character device or a FIFO is *written through*: opened and written, never replaced;
/// - a symbolic link is followed (up to 40 links), so the link stays and what it names is
///   replaced or written through as above;
/// - a missing parent folder is an error: tumble creates only `--out` folders, never the folder
///   of an explicit file path; a folder, a block device or a socket is an error too.
/// Every error is tumble::Error (Environment, exit 3) naming the path as given.

#include <filesystem>
#include <string_view>

namespace tumble {

struct OutputTarget {
  enum class Kind {
    Replace,       ///< a regular file or nothing: renamed over
    WriteThrough,  ///< a character device or FIFO: opened and written
  };
  std::filesystem::path path;      ///< as given (for messages and run.json)
  std::filesystem::path resolved;  ///< symbolic links followed: where the bytes go
  Kind kind = Kind::Replace;
};

/// Looks at what `path` names now. Throws tumble::Error (Environment) for a missing parent
/// folder, a folder, a block device, a socket or a loop of links.
OutputTarget output_target(const std::filesystem::path& path);

/// Puts the finished regular file `finished` in place at `target`: Replace renames it over
/// `target.resolved` (a copy beside it first when the two are on different file systems);
/// WriteThrough copies its bytes into the device or FIFO (waiting for a FIFO's reader, as
/// ffmpeg does) and removes it. Throws tumble::Error (Environment); `finished` is then left for
/// its owner to remove.
void place_output(const std::filesystem::path& finished, const OutputTarget& target);

/// A new, empty file in `folder` with a name no other process or thread has:
/// `.<stem>.XXXXXX.partial` (six random letters and digits, created with O_EXCL as mkstemp
/// does). The dot keeps it out of globs like `*.png`; `.partial` says what it is.
std::filesystem::path make_unique_temporary_file(const std::filesystem::path& folder,
                                                 std::string_view stem);
/// The same for a new, empty folder (as mkdtemp).
std::filesystem::path make_unique_temporary_folder(const std::filesystem::path& folder,
                                                   std::string_view stem);

}  // namespace tumble
