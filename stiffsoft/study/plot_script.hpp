#pragma once
/// @file The matplotlib script that draws a study's plots from its plot_data.json.

namespace stiffsoft::study {

/// Python 3 source: `python3 plot.py plot_data.json` writes the PNGs next to the JSON file.
extern const char* const kPlotScript;

}  // namespace stiffsoft::study
