// Toolpath files moved to the toolpath area (rosmill/toolpath/toolpath_io.hpp); this name stays only until the
// program pipeline's own files (src/cli/cmd_post.cpp) include the new one.
#pragma once
#include "rosmill/toolpath/toolpath_io.hpp"
