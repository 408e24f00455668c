#pragma once
/// @file Conservative linear continuous collision detection: point–triangle and edge–edge.

#include <stiffsoft/coupling/ccd/ccd_settings.hpp>
#include <stiffsoft/coupling/ccd/edge_edge_ccd.hpp>
#include <stiffsoft/coupling/ccd/point_triangle_ccd.hpp>
