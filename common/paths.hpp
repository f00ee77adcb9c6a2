// Where the project's files are at run time, so that a relative path in config ("data/skin/...") works
// from the project root, from build/, and from an installed copy (cmake --install, the .deb).
#pragma once

#include <string>

namespace gpilot {

// The project root, the folder that relative data paths ("data/...", "deploy/...") are taken from:
//  1. $GPILOT_ROOT if set;
//  2. an installed copy: <folder of this executable>/../share/gesture-pilot when it exists (the prefix is
//     found at run time, so an installed tree works wherever it is put, without the checkout);
//  3. the source tree this binary was built from (runs from build/).
std::string project_root();

// The installed data folder of the executable at exe_path (<exe dir>/../share/gesture-pilot) if it exists, else "".
std::string installed_data_dir(const std::string& exe_path);

// path unchanged if absolute or if it exists relative to the working directory; else project_root()/path.
std::string resolve_project_path(const std::string& path);

}  // namespace gpilot
