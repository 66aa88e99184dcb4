// Whole files in and out, for xshade's own files (cache entries, reports, goldens).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"

namespace xshade {

// Why read_file gave nothing.
enum class ReadFailure { CannotOpen, IsDirectory, NotAFile, CannotRead };

// The file's bytes, or nothing when it cannot be read (and, where `why` is given, why not). Only
// a regular file (or a link to one) is read: a FIFO, socket or device is NotAFile, never waited on.
std::optional<std::string> read_file(const std::filesystem::path& path, ReadFailure* why = nullptr);
// read_file of a path a stat has just found a regular file of `known_size` bytes: without asking
// again (the front end reads a few includes for every compile, and each question is a system
// call). A file that has grown since is still read whole.
std::optional<std::string> read_regular_file(const std::filesystem::path& path, size_t known_size,
                                             ReadFailure* why = nullptr);

// The largest shader sources people write (Unity's Standard shader's includes) are some 100 KB;
// a generated one can be a few MB. Past 16 MiB a file is not a shader (HLSL or ShaderLab), and
// the readers refuse it unread.
inline constexpr size_t kMaxSourceFileBytes = size_t(16) << 20;

// What is at `path` when it is not a regular file, as a message says it: "a directory", "a FIFO",
// "a socket", "a device", "a symbolic link to nothing"; empty for a regular file, a link to one,
// or nothing at all.
std::string not_a_file(const std::filesystem::path& path);

// A file a user gave (a scene, a project file, a manifest, a report's results) read whole, after
// opening it without waiting (a FIFO is not waited on) and checking it: not there, not a regular
// file (not_a_file), or more than `max_bytes` bytes is a user's error naming `what` and the path,
// before anything is read; a read that fails is the environment's error with the errno.
Result<std::string> read_input_file(const std::filesystem::path& path, size_t max_bytes, std::string_view what);

// `from` written whole to `to` (write_file_atomically): a copy that fails leaves no part of it.
// A `from` that cannot be read and a `to` that cannot be written are the environment's errors.
Result<void> copy_file_whole(const std::filesystem::path& from, const std::filesystem::path& to);

// A folder only this user can write, for what xshade trusts without checking who wrote it (the
// compile cache): made with mode 0700 where it is missing; where it is there, it must be a
// directory owned by this user that neither the group nor others can write, or the error says
// what is wrong with it (another user could have put files in it for xshade to believe).
Result<void> make_private_folder(const std::filesystem::path& folder);

// Writes all of `bytes` to the open descriptor, through short writes and interruptions; false
// (with errno set) when the descriptor takes no more.
bool write_all(int fd, std::string_view bytes);

// Writes to a temporary file beside `path` with a unique name, then renames it into place: a
// reader sees the old file or the new one, never half of one, an interrupted write leaves no
// torn file, and several processes may write the same file at once. Not synced to disk: what
// must survive a power cut syncs itself (the golden store), or checks what it reads (the cache).
Result<void> write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace xshade
