#pragma once
/// @file A contact sheet: a few pictures of a run side by side in one PNG, for a README or a report.

#include <filesystem>
#include <vector>

namespace stiffsoft {

/// The indices of `count` pictures out of `total`, evenly spaced, first and last included.
std::vector<int> sheet_picks(int total, int count);

/// Writes `pictures` (PNG files of one size), scaled by `scale`, in rows of `columns` on white
/// with a thin gap, to `sheet`. std::runtime_error naming the file when one cannot be read.
void write_contact_sheet(const std::vector<std::filesystem::path>& pictures, int columns, double scale,
                         const std::filesystem::path& sheet);

}  // namespace stiffsoft
