#pragma once
/// @file Per-stencil math of IPC contact: distances, classification, barrier, edge–edge
/// mollifier, barrier potential, lagged friction, PSD projection (one include for all).

#include "coupling/contact/barrier.hpp"
#include "coupling/contact/barrier_potential.hpp"
#include "coupling/contact/distance_classification.hpp"
#include "coupling/contact/edge_edge_mollifier.hpp"
#include "coupling/contact/friction.hpp"
#include "coupling/contact/primitive_pair.hpp"
#include "coupling/contact/psd_projection.hpp"
#include "coupling/contact/squared_distance.hpp"
