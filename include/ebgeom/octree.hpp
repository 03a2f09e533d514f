#pragma once
/// \file
/// Module umbrella: the generic octree.

#include "ebgeom/octree/octree.hpp"
