// libtex: programmable element textures (thesis Chapter 3). One include for scripts.
#pragma once

#include "libtex/arrangement.hpp"
#include "libtex/cells.hpp"
#include "libtex/curves.hpp"
#include "libtex/error.hpp"
#include "libtex/fields.hpp"
#include "libtex/geometry.hpp"
#include "libtex/labels.hpp"
#include "libtex/mapping.hpp"
#include "libtex/mappers.hpp"
#include "libtex/merge.hpp"
#include "libtex/parallel.hpp"
#include "libtex/partitions.hpp"
#include "libtex/planar_map.hpp"
#include "libtex/random.hpp"
#include "libtex/region.hpp"
#include "libtex/svg.hpp"
