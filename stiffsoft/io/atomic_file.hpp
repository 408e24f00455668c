#pragma once
/// @file Whole-file-or-nothing writes: a killed run never leaves a half-written output file.

#include <filesystem>
#include <functional>
#include <ostream>

namespace stiffsoft {

/// Writes `path` atomically: `write(std::ostream&)` fills a temporary file in the same folder
/// (`.<name>.tmp.<pid>.<n>`), which is flushed, checked and then renamed over `path` with
/// std::filesystem::rename (atomic on POSIX file systems within one folder).
///
/// Throws std::runtime_error naming the file when the temporary cannot be created, when the
/// stream goes bad while writing or closing (e.g. disk full), or when the rename fails. If
/// `write` itself throws, its exception is rethrown unchanged. In every failure case the
/// temporary is removed and the old content of `path` (if any) stays intact.
///
/// Safe against the process being killed at any point; not against power loss (no fsync).
/// The folder of `path` must exist.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

/// Removes the temporaries (`.<name>.tmp.<pid>.<n>`) that a killed writer left in `folder` and
/// below it; returns how many. For a run resumed in its output folder.
int remove_stale_temporaries(const std::filesystem::path& folder);

}  // namespace stiffsoft
