#pragma once
// The meshing sources' name for the shared work-sharing loop (also used by reconstruction/clouds).
#include "interlin/reconstruction/meshing/parallel_for.h"
