#pragma once
/// \file
/// Module umbrella: polygon soups, half-edge and triangle meshes, validation.

#include "ebgeom/mesh/polygon_soup.hpp"
