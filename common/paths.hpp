// Where the project's files are at run time, so that a relative path in config ("data/skin/...") works
// from the project root, from build/, and from an installed copy.
#pragma once

#include <string>

namespace gpilot {

// The project root: $GPILOT_ROOT if set, else the source tree this binary was built from.
std::string project_root();

// path unchanged if absolute or if it exists relative to the working directory; else project_root()/path.
std::string resolve_project_path(const std::string& path);

}  // namespace gpilot
