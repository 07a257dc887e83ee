#pragma once
/// @file private_directory.hpp
/// A directory a (possibly privileged) process writes its files into (the core's black boxes
/// and emergency-stop latch, the black box of a lost core): opened once at setup and checked
/// to be one that only the controller's user (or root) can write; files are created in it
/// exclusively, never through a link, readable by their owner only. Written with a plain
/// std::ofstream to a predictable name in /tmp, a black box of a root core followed a symlink a
/// local user had planted there and overwrote its target (J4 review of f3c5aec, 3 of 3).
///
/// Setup and shutdown code only: every function may allocate, make syscalls and throw
/// std::runtime_error (with the path and the reason); none is for the cycle.

#include <string>
#include <string_view>
#include <vector>

namespace hapticctrl::program {

class PrivateDirectory {
 public:
  /// Opens `path` without following a symlink there and checks it: a directory, owned by this
  /// process's user or by root, that neither its group nor others may write (the checks are made
  /// on the open directory, so it cannot be swapped after them). Throws std::runtime_error saying
  /// what is wrong and what to do.
  explicit PrivateDirectory(std::string path);
  ~PrivateDirectory();
  PrivateDirectory(const PrivateDirectory&) = delete;
  PrivateDirectory& operator=(const PrivateDirectory&) = delete;
  PrivateDirectory(PrivateDirectory&& other) noexcept;
  PrivateDirectory& operator=(PrivateDirectory&& other) noexcept;

  [[nodiscard]] const std::string& path() const noexcept { return path_; }

  /// Creates the file `name` (a plain name, no '/') with O_CREAT | O_EXCL | O_NOFOLLOW, mode 0600
  /// whatever the umask, writes `text` and syncs it. Returns false, writing nothing, when `name`
  /// exists (a file, or a link planted there: never followed); throws on any other failure.
  bool create_file(const std::string& name, std::string_view text) const;

  /// The regular files whose names start with `prefix` and end with `suffix`, oldest first (by
  /// modification time, then name).
  [[nodiscard]] std::vector<std::string> files(std::string_view prefix,
                                               std::string_view suffix) const;

  /// True when something (a file, a link, anything) is there under `name`.
  [[nodiscard]] bool contains(const std::string& name) const;

  /// The text of the regular file `name` (never through a link): empty when it is not a
  /// regular file or cannot be read.
  [[nodiscard]] std::string read_file(const std::string& name) const;

  /// Adds `text` to a kept series of files: creates `<prefix><stem><suffix>` as create_file()
  /// does (a name already there, a link included, is left alone and `.2`, `.3`, ... goes before
  /// the suffix instead), then removes the series' oldest files (`<prefix>*<suffix>`) beyond
  /// `keep`; the new one always stays. Returns the new file's path. Throws std::runtime_error.
  std::string add_to_series(const std::string& prefix, const std::string& stem,
                            const std::string& suffix, std::string_view text,
                            std::size_t keep) const;

  /// Removes `name` (a link is removed, not its target). False when it was not there.
  bool remove(const std::string& name) const;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace hapticctrl::program
