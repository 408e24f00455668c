#pragma once
/// @file The colour scales of `stiffsoft render`: the maps of stiffsoft/io/colour_maps.hpp over
/// ranges taken from the rendered frames.

#include <vtkColorTransferFunction.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

#include <stiffsoft/io/colour_maps.hpp>

namespace stiffsoft {

/// The ranges of the colour scales: each runs from 0 to the kRangeQuantile quantile of the
/// per-frame largest values (the arrows to the largest contact force of all frames).
class ColourScales {
 public:
  /// Adds one frame's largest values.
  void extend(vtkMultiBlockDataSet* frame);
  /// Top of the von Mises range of soft bodies, Pa.
  double stress_top() const;
  /// Top of the speed range of affine bodies, m/s.
  double speed_top() const;
  /// The largest contact force on one vertex, N.
  double contact_force_top() const { return m_contact_force; }

 private:
  std::vector<double> m_von_mises;  ///< per frame: largest von Mises stress of a soft body's cell, Pa
  std::vector<double> m_speed;      ///< per frame: largest speed of an affine body's vertex, m/s
  double m_contact_force = 0;       ///< largest contact force on one vertex so far, N
};

/// A block's `model` field data ("affine", "soft", "fixed", "kinematic"), or "" without one.
std::string block_model(vtkDataObject* block);

/// The map `colours` (evenly spaced samples) from 0 to `top`.
vtkSmartPointer<vtkColorTransferFunction> colour_map(const std::vector<Rgb>& colours, double top);

}  // namespace stiffsoft
