#pragma once
/// @file Conservative linear continuous collision detection: point–triangle and edge–edge.

#include "coupling/ccd/ccd_settings.hpp"
#include "coupling/ccd/edge_edge_ccd.hpp"
#include "coupling/ccd/point_triangle_ccd.hpp"
