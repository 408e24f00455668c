#pragma once
/// @file Per-stencil math of IPC contact: distances, classification, barrier, edge–edge
/// mollifier, barrier potential, lagged friction, PSD projection (one include for all).

#include <stiffsoft/coupling/contact/barrier.hpp>
#include <stiffsoft/coupling/contact/barrier_potential.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>
#include <stiffsoft/coupling/contact/edge_edge_mollifier.hpp>
#include <stiffsoft/coupling/contact/friction.hpp>
#include <stiffsoft/coupling/contact/primitive_pair.hpp>
#include <stiffsoft/coupling/contact/psd_projection.hpp>
#include <stiffsoft/coupling/contact/squared_distance.hpp>
