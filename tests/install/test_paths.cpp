// common/paths: an installed binary finds its data beside it (<exe dir>/../share/gesture-pilot), wherever the
// installed tree is; a binary without that folder gets "" (and falls back to GPILOT_ROOT or the source tree).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "paths.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

struct TempTree {
  fs::path root = fs::temp_directory_path() / ("gpilot-paths-" + std::to_string(::getpid()));
  TempTree() { fs::create_directories(root / "bin"); std::ofstream(root / "bin" / "gpilot-x") << "x"; }
  ~TempTree() { fs::remove_all(root); }
};

TEST(InstalledDataDir, FoundBesideTheExecutable) {
  // GIVEN an installed tree P/bin/gpilot-x with P/share/gesture-pilot
  TempTree t;
  fs::create_directories(t.root / "share" / "gesture-pilot");
  // WHEN its data folder is asked for, THEN it is P/share/gesture-pilot (canonical, no "..")
  EXPECT_EQ(installed_data_dir((t.root / "bin" / "gpilot-x").string()),
            (fs::canonical(t.root) / "share" / "gesture-pilot").string());
}

TEST(InstalledDataDir, FoundThroughASymlinkToTheExecutable) {
  // GIVEN /usr/local/bin-style link to an installed binary: the data is the binary's, not the link's
  TempTree t;
  fs::create_directories(t.root / "share" / "gesture-pilot");
  fs::create_directories(t.root / "elsewhere");
  fs::create_symlink(t.root / "bin" / "gpilot-x", t.root / "elsewhere" / "gpilot-x");
  EXPECT_EQ(installed_data_dir((t.root / "elsewhere" / "gpilot-x").string()),
            (fs::canonical(t.root) / "share" / "gesture-pilot").string());
}

TEST(InstalledDataDir, EmptyWithoutTheShareFolder) {
  // GIVEN a binary with no share/gesture-pilot beside it (a build tree), THEN none; a missing binary: none
  TempTree t;
  EXPECT_EQ(installed_data_dir((t.root / "bin" / "gpilot-x").string()), "");
  EXPECT_EQ(installed_data_dir((t.root / "bin" / "missing").string()), "");
}

TEST(ProjectRoot, EnvironmentWins) {
  ::setenv("GPILOT_ROOT", "/some/where", 1);
  EXPECT_EQ(project_root(), "/some/where");
  EXPECT_EQ(resolve_project_path("data/skin/skin_model.yaml"), "/some/where/data/skin/skin_model.yaml");
  EXPECT_EQ(resolve_project_path("/abs/file.yaml"), "/abs/file.yaml");
  ::unsetenv("GPILOT_ROOT");
}

}  // namespace
}  // namespace gpilot
