// gpilot-synth-sheet: one PNG contact sheet of a scenario's key poses, each tile cropped around the person
// with its ground truth drawn: user box, face box, p_uc and p_bc, hand squares, the expected vector and
// the intended gesture and the paper's command on it. For the README and for reviewers.
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture/capture_params.hpp"
#include "capture/synthetic_world.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "service_cli.hpp"

using namespace gpilot;

namespace {

const char* kModes[] = {"HOVER", "FINE", "UP", "DOWN", "CLOSER", "FURTHER"};
const char* kKinds[] = {"NONE", "OUT", "FRONT"};

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& colour) {
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar::all(0), 4, cv::LINE_AA);
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

// The frame with its truth drawn, cropped around the person (room for a stretched arm) and scaled to height h.
cv::Mat tile(const SyntheticFrame& f, double t, int h) {
  const SyntheticTruth& g = f.truth;
  cv::Mat img = f.bgr.clone();
  const cv::Scalar green(0, 220, 0), cyan(255, 220, 0), magenta(255, 0, 255), yellow(0, 230, 255);
  cv::rectangle(img, g.user_box, green, 1, cv::LINE_AA);
  cv::rectangle(img, g.face_box, cyan, 1, cv::LINE_AA);
  for (const auto& hand : {g.right_hand, g.left_hand})
    cv::rectangle(img, cv::Rect2f(hand.x - g.hand_size / 2, hand.y - g.hand_size / 2, g.hand_size, g.hand_size), yellow, 1, cv::LINE_AA);
  cv::drawMarker(img, g.shoulder_centre, magenta, cv::MARKER_CROSS, 8, 1, cv::LINE_AA);
  cv::drawMarker(img, g.body_centre, magenta, cv::MARKER_SQUARE, 6, 1, cv::LINE_AA);
  if (g.expected_kind != 0) {
    const cv::Point2f from = g.expected_kind == 1 ? g.shoulder_centre : g.body_centre;
    cv::arrowedLine(img, from, from + g.expected_vector, cv::Scalar(0, 0, 255), 2, cv::LINE_AA, 0, 0.15);
  }
  const cv::Rect2f& u = g.user_box;
  cv::Rect crop(cv::Point(static_cast<int>(u.x - 1.7f * u.width), static_cast<int>(u.y - 0.3f * u.height)),
                cv::Point(static_cast<int>(u.x + 2.7f * u.width), static_cast<int>(u.y + 1.08f * u.height)));
  crop &= cv::Rect(0, 0, img.cols, img.rows);
  // The person out of view (walked out of the frame): the whole frame.
  if (crop.width < u.width || crop.height < 0.5f * u.height) crop = cv::Rect(0, 0, img.cols, img.rows);
  cv::Mat out;
  cv::resize(img(crop), out, cv::Size(static_cast<int>(std::lround(crop.width * double(h) / crop.height)), h), 0, 0, cv::INTER_AREA);
  char line[160];
  std::snprintf(line, sizeof line, "t %.1f s  %s", t, gesture_name(g.gesture));
  text(out, line, {6, 22}, 0.6, cv::Scalar(255, 255, 255));
  std::snprintf(line, sizeof line, "%s -> %s (%.2f, %.2f, %.0f)", kKinds[std::clamp(g.expected_kind, 0, 2)],
                kModes[std::clamp(g.expected_mode, 0, 5)], g.expected_direction.x, g.expected_direction.y, g.expected_direction.z);
  text(out, line, {6, h - 10}, 0.5, cv::Scalar(200, 255, 200));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  ServiceCli cli("gpilot-synth-sheet",
                 "Writes one PNG contact sheet of a synthetic scenario's key poses with the ground truth drawn on them:\n"
                 "user box (green), face box (cyan), shoulder centre p_uc (cross) and body centre p_bc (square), hand\n"
                 "squares (yellow), the expected hand vector (red arrow), and per tile the intended gesture and the\n"
                 "kind/mode/direction the paper's rules give on the true hands.");
  std::string scenario = "tour", out;
  uint64_t seed = 1;
  int columns = 5, tile_height = 360;
  auto& app = cli.app();
  app.add_option("scenario", scenario, "scenario name (deploy/scenarios/NAME.yaml) or path (default tour)");
  app.add_option("--out", out, "PNG to write (default: synth-sheet-NAME.png)");
  app.add_option("--seed", seed, "synthetic world seed");
  app.add_option("--columns", columns, "tiles per row")->check(CLI::Range(1, 20));
  app.add_option("--tile-height", tile_height, "tile height, pixels")->check(CLI::Range(120, 1080));
  return cli.run(argc, argv, [&](const Config& config) {
    const SyntheticWorld world(config.section<CaptureParams>("capture").synthetic, Scenario::load(scenario), seed);
    if (out.empty()) out = "synth-sheet-" + world.scenario().name() + ".png";
    std::vector<cv::Mat> tiles;
    int64_t index = 0;
    for (double t : world.scenario().key_times()) {
      const SyntheticFrame f = world.render(t, index++, std::nullopt);
      tiles.push_back(tile(f, t, tile_height));
      std::fprintf(stderr, "\r%zu/%zu poses", tiles.size(), world.scenario().key_times().size());
    }
    std::fprintf(stderr, "\n");
    int tile_w = 0;
    for (const auto& m : tiles) tile_w = std::max(tile_w, m.cols);
    const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
    cv::Mat sheet(rows * tile_height, std::min<int>(columns, static_cast<int>(tiles.size())) * tile_w, CV_8UC3, cv::Scalar::all(30));
    for (size_t i = 0; i < tiles.size(); ++i) {
      const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
      tiles[i].copyTo(sheet(cv::Rect(c * tile_w, r * tile_height, tiles[i].cols, tiles[i].rows)));
    }
    if (!cv::imwrite(out, sheet)) throw std::runtime_error("cannot write '" + out + "'");
    std::printf("%s: %zu poses of scenario '%s'\n", out.c_str(), tiles.size(), world.scenario().name().c_str());
    return 0;
  });
}
