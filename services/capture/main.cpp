// gpilot-capture: frames from a camera, a video file, an image folder or the synthetic world (the default).
// Writes CAMERA (gpilot.image_t; BGR8, GRAY8 or JPEG by capture.pixel_format), GROUND_TRUTH
// (gpilot.ground_truth_t, synthetic world only, same seq and utime as its frame) and HEALTH; reads
// VEHICLE_STATE (the synthetic camera flies with the vehicle). See capture_service.hpp for utime.
#include "capture_service.hpp"
#include "service_cli.hpp"

using namespace gpilot;

int main(int argc, char** argv) {
  ServiceCli cli("gpilot-capture",
                 "Capture: publishes CAMERA frames from one source, paced in real time.\n"
                 "  --synthetic SCENARIO  the synthetic world (default: tour): a person gesturing in front of a photo,\n"
                 "                        seen from VEHICLE_STATE's pose (else the scenario's); also GROUND_TRUTH\n"
                 "  --video FILE          a video file (FFmpeg), at its frame rate; --loop to repeat\n"
                 "  --images DIR          image files in name order, at capture.fps; --loop to repeat\n"
                 "  --camera N            V4L2 camera N, asked for capture.width x height @ fps; retried if lost\n"
                 "Ends (status 0) at the end of the scenario or file, or after --duration; a source that cannot open\n"
                 "exits with status 1. Reads VEHICLE_STATE; writes CAMERA, GROUND_TRUTH, HEALTH. Config: capture.");
  CaptureOptions o;
  std::string synthetic, video, images;
  int camera = -1;
  auto& app = cli.app();
  auto* s_opt = app.add_option("--synthetic", synthetic, "scenario name (deploy/scenarios/NAME.yaml) or YAML path");
  auto* v_opt = app.add_option("--video", video, "video file");
  auto* i_opt = app.add_option("--images", images, "folder of images");
  auto* c_opt = app.add_option("--camera", camera, "V4L2 camera index")->check(CLI::NonNegativeNumber);
  s_opt->excludes(v_opt)->excludes(i_opt)->excludes(c_opt);
  v_opt->excludes(i_opt)->excludes(c_opt);
  i_opt->excludes(c_opt);
  app.add_flag("--loop", o.loop, "video / images: start again at the end");
  app.add_flag("--as-fast-as-possible", o.as_fast_as_possible, "video / images / synthetic: no real-time pacing");
  app.add_option("--duration", o.duration_s, "stop after this many seconds of frames (0 = until the source ends)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--seed", o.seed, "synthetic world seed (sensor noise, camera shake)");
  return cli.run_node(argc, argv, [&](const Config& config, BusNode& node) {
    if (!video.empty()) o.kind = CaptureOptions::Kind::Video, o.source = video;
    else if (!images.empty()) o.kind = CaptureOptions::Kind::Images, o.source = images;
    else if (camera >= 0) o.kind = CaptureOptions::Kind::Camera, o.camera_index = camera;
    else if (!synthetic.empty()) o.source = synthetic;
    return run_capture(config, o, node);
  });
}
