// Writes the seed corpora of the fuzz targets: usage gpilot-fuzz-seeds TESTS_FUZZ_DIR (tests/fuzz). Each
// seed is small; libFuzzer grows the rest. The byte layouts of the structured targets follow their readers
// (fuzz_input.hpp: little-endian, a flag byte before each optional field).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gpilot/config_t.hpp"
#include "gpilot/flight_control_t.hpp"
#include "gpilot/autopilot_t.hpp"
#include "gpilot/flight_setpoint_t.hpp"
#include "gpilot/gesture_cmd_t.hpp"
#include "gpilot/ground_truth_t.hpp"
#include "gpilot/hand_obs_t.hpp"
#include "gpilot/health_t.hpp"
#include "gpilot/image_t.hpp"
#include "gpilot/tracker_init_t.hpp"
#include "gpilot/user_track_t.hpp"
#include "gpilot/vehicle_state_t.hpp"
#include "image_codec.hpp"
#include "mavlink/frame.hpp"
#include "mavlink/messages.hpp"

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

namespace {

fs::path root;

void write(const std::string& target, const std::string& name, const Bytes& b) {
  fs::create_directories(root / target);
  std::ofstream(root / target / ("seed-" + name), std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
}

template <class Msg>
Bytes encode(const Msg& m) {
  Bytes b(static_cast<size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

template <class T>
void put(Bytes& b, T v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  b.insert(b.end(), p, p + sizeof(T));
}

cv::Mat pattern(int w, int h) {
  cv::Mat m(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(x * 9 % 256, y * 7 % 256, (x + y) * 5 % 256);
  return m;
}

// fuzz_decode.cpp's layout: the type's index (image_t 0, tracker_init_t 1, ... health_t 9, config_t 10), the
// datagram.
Bytes typed(uint8_t type, Bytes datagram) {
  datagram.insert(datagram.begin(), type);
  return datagram;
}

void decode_seeds() {
  using namespace gpilot;
  const image_t img = mat_to_image(pattern(8, 6), 1, 2);
  write("decode", "image-bgr", typed(0, encode(img)));
  write("decode", "image-jpeg", typed(0, encode(mat_to_image(pattern(16, 8), 1, 2, image_t::PIXEL_FORMAT_JPEG, 50))));
  tracker_init_t ti{};
  ti.command = tracker_init_t::COMMAND_SET_BOX;
  ti.box[2] = ti.box[3] = 40;
  ti.source = "fuzz";
  write("decode", "tracker-init", typed(1, encode(ti)));
  user_track_t ut{};
  ut.status = user_track_t::STATUS_TRACKING;
  ut.box[0] = 100, ut.box[1] = 50, ut.box[2] = 200, ut.box[3] = 400;
  ut.image_width = 640, ut.image_height = 480;
  write("decode", "user-track", typed(2, encode(ut)));
  hand_obs_t ho{};
  ho.track_status = user_track_t::STATUS_TRACKING;
  ho.kind = hand_obs_t::KIND_OUT;
  ho.user_box[2] = 120, ho.user_box[3] = 300;
  ho.image_width = 640, ho.image_height = 480;
  write("decode", "hand-obs", typed(3, encode(ho)));
  gesture_cmd_t gc{};
  gc.mode = gesture_cmd_t::MODE_FINE;
  gc.direction[0] = 0.5f;
  gc.user_box_width = 120;
  write("decode", "gesture-cmd", typed(4, encode(gc)));
  flight_control_t fc{};
  fc.command = flight_control_t::COMMAND_ENGAGE;
  fc.source = "gpilot-ctl";
  write("decode", "flight-control", typed(5, encode(fc)));
  flight_setpoint_t fs{};
  write("decode", "flight-setpoint", typed(6, encode(fs)));
  vehicle_state_t vs{};
  vs.source = vehicle_state_t::SOURCE_SIMULATOR;
  write("decode", "vehicle-state", typed(7, encode(vs)));
  ground_truth_t gt{};
  write("decode", "ground-truth", typed(8, encode(gt)));
  health_t h{};
  h.name = "gpilot-tracker";
  h.state_detail = "tracking";
  write("decode", "health", typed(9, encode(h)));
  config_t cfg{};
  cfg.process = "gpilot-decide";
  cfg.pid = 4242;
  cfg.yaml = "decide:\n  buffer_size: 60\n";
  write("decode", "config", typed(10, encode(cfg)));
  autopilot_t ap{};
  ap.kind = autopilot_t::KIND_PARAM_VALUE;
  ap.param_id = "COM_OF_LOSS_T";
  ap.param_value = 0.5f;
  ap.param_type = 9;  // MAV_PARAM_TYPE_REAL32
  write("decode", "autopilot", typed(11, encode(ap)));
  // The one-datagram kills: a string length of 0 and of -1 (FLIGHT_CONTROL, 33 bytes).
  Bytes fc_bytes = encode(fc);
  const size_t len_at = fc_bytes.size() - fc.source.size() - 1 - 4;
  for (int32_t bad : {0, -1}) {
    Bytes b(fc_bytes.begin(), fc_bytes.begin() + static_cast<long>(len_at));
    for (int i = 3; i >= 0; --i) b.push_back(static_cast<uint8_t>(static_cast<uint32_t>(bad) >> (8 * i)));
    write("decode", "flight-control-string-length-" + std::to_string(bad), typed(5, b));
  }
}

// fuzz_image.cpp's layout: utime, seq, mode, width (flag, value), height (flag, value), stride (flag, extra), data.
Bytes image_input(uint8_t mode, uint32_t w, uint32_t h, const Bytes& data) {
  Bytes b;
  put<int64_t>(b, 1);
  put<int64_t>(b, 2);
  put<uint8_t>(b, mode);
  put<uint8_t>(b, 0), put<uint32_t>(b, w);
  put<uint8_t>(b, 0), put<uint32_t>(b, h);
  put<uint8_t>(b, 0), put<uint8_t>(b, 0);
  b.insert(b.end(), data.begin(), data.end());
  return b;
}

void image_seeds() {
  using namespace gpilot;
  const image_t bgr = mat_to_image(pattern(8, 6), 0, 0);
  write("image", "bgr", image_input(2, 8, 6, bgr.data));
  const image_t grey = mat_to_image(pattern(8, 6), 0, 0, image_t::PIXEL_FORMAT_GRAY8);
  write("image", "grey", image_input(1, 8, 6, grey.data));
  for (int q : {30, 90}) {
    const image_t j = mat_to_image(pattern(16, 16), 0, 0, image_t::PIXEL_FORMAT_JPEG, q);
    write("image", "jpeg-q" + std::to_string(q), image_input(3 | 8, 16, 16, j.data));
  }
  cv::Mat g(8, 24, CV_8UC1, cv::Scalar(77));
  const image_t jg = mat_to_image(g, 0, 0, image_t::PIXEL_FORMAT_JPEG, 75);
  write("image", "jpeg-grey", image_input(3 | 8, 24, 8, jg.data));
}

void mavlink_seeds() {
  namespace mav = gpilot::mavlink;
  auto frame = [](uint32_t id, const Bytes& payload) {
    mav::Frame f;
    f.sysid = 1, f.compid = 1, f.msgid = id, f.payload = payload;
    return mav::encode_frame(f);
  };
  mav::Heartbeat hb;
  hb.type = 2, hb.autopilot = 12, hb.base_mode = 128 | 1;
  mav::Attitude att;
  att.yaw = 0.5f;
  mav::LocalPositionNed pos;
  pos.z = -1.5f;
  mav::CommandAck ack;
  ack.command = 400;
  mav::ExtendedSysState ext;
  ext.landed_state = 2;
  mav::SetPositionTargetLocalNed sp;
  sp.vx = 0.5f, sp.type_mask = 0x0DC7;
  mav::CommandLong cl;
  cl.command = 400, cl.param[0] = 1;
  Bytes stream;
  for (const Bytes& f : {frame(mav::Heartbeat::kId, mav::pack(hb)), frame(mav::Attitude::kId, mav::pack(att)),
                         frame(mav::LocalPositionNed::kId, mav::pack(pos)), frame(mav::CommandAck::kId, mav::pack(ack)),
                         frame(mav::ExtendedSysState::kId, mav::pack(ext)),
                         frame(mav::SetPositionTargetLocalNed::kId, mav::pack(sp)),
                         frame(mav::CommandLong::kId, mav::pack(cl))})
    stream.insert(stream.end(), f.begin(), f.end());
  Bytes one_datagram{0};
  one_datagram.insert(one_datagram.end(), stream.begin(), stream.end());
  write("mavlink", "one-datagram", one_datagram);
  Bytes pieces{0x80 | 7};  // a stream in 7-byte pieces
  pieces.insert(pieces.end(), stream.begin(), stream.end());
  write("mavlink", "stream-pieces", pieces);
}

void config_seeds(const fs::path& project) {
  std::ifstream in(project / "deploy/config/default.yaml", std::ios::binary);
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write("config", "default", Bytes(yaml.begin(), yaml.end()));
  const std::string small = "hands.lambda1=0.75\nhands:\n  lambda2: 0.2\n  skin:\n    threshold: 0.6\ndecide: {buffer_size: 40}\n";
  write("config", "small", Bytes(small.begin(), small.end()));
  const std::string bad = "\ntracker:\n  dsst: [1, 2]\nflight:\n  gain_horizontal: .nan\n";
  write("config", "bad", Bytes(bad.begin(), bad.end()));
}

void stage_seeds() {
  // tracker: a manual box (op 0, four coordinates), then photo frames (op 2, 48x48, crop kind 2).
  Bytes t;
  put<uint8_t>(t, 0);
  for (uint16_t v : {64, 64, 160, 160}) put<uint8_t>(t, 0), put<uint16_t>(t, static_cast<uint16_t>(v * 4));
  for (int i = 0; i < 4; ++i) {
    put<uint8_t>(t, 2);
    put<uint32_t>(t, 44), put<uint32_t>(t, 44);  // in(4, 48): 4 + 44
    put<uint8_t>(t, 2);                          // photo crop
    put<uint32_t>(t, 80), put<uint32_t>(t, static_cast<uint32_t>(10 + i)), put<uint32_t>(t, 8);
    put<uint8_t>(t, 0);  // colour
  }
  write("tracker", "manual-box-photo", t);
  Bytes s;  // face search on photo frames only
  for (int i = 0; i < 3; ++i) {
    put<uint8_t>(s, 3);
    put<uint32_t>(s, 44), put<uint32_t>(s, 44), put<uint8_t>(s, 2);
    put<uint32_t>(s, 112), put<uint32_t>(s, 0), put<uint32_t>(s, 0), put<uint8_t>(s, 0);
  }
  write("tracker", "photo-search", s);

  // hands: photo frames 64x64 (in(4, 96): 60), BGR8, a tracking box over most of the frame, then a face box.
  Bytes h;
  for (int i = 0; i < 3; ++i) {
    put<uint32_t>(h, 60), put<uint32_t>(h, 60), put<uint8_t>(h, 2);
    put<uint32_t>(h, 112), put<uint32_t>(h, 4), put<uint32_t>(h, 4);
    put<uint8_t>(h, static_cast<uint8_t>(i == 2 ? 0 : 200));  // JPEG on the last
    put<uint8_t>(h, 1), put<uint32_t>(h, 1), put<uint8_t>(h, 0);  // TRACKING, track 1, sizes of the frame
    for (uint16_t v : {16, 4, 32, 60}) put<uint8_t>(h, 0), put<uint16_t>(h, static_cast<uint16_t>(v * 64));
    put<uint8_t>(h, 1);
    for (uint16_t v : {24, 8, 16, 16}) put<uint8_t>(h, 0), put<uint16_t>(h, static_cast<uint16_t>(v * 64));
    put<uint8_t>(h, 0), put<uint16_t>(h, 40);
    put<uint8_t>(h, 1);
  }
  write("hands", "photo-track-face", h);

  // decide: 40 observations 33 ms apart, one user tracking, OUT to the right.
  Bytes d{0};
  put<uint32_t>(d, 0);
  for (int i = 0; i < 40; ++i) {
    put<uint8_t>(d, 0), put<uint8_t>(d, 0), put<uint8_t>(d, 1);
    put<uint8_t>(d, 0), put<uint16_t>(d, 0);        // box width 120
    put<uint8_t>(d, 0);                              // keep it
    put<uint8_t>(d, 0), put<uint16_t>(d, 1500);      // vector x = 1500/4/4 - 256 + ...: to the right
    put<uint8_t>(d, 0), put<uint16_t>(d, 1024);
  }
  write("decide", "out-right", d);

  // flight: engage, track, command, vehicle, then ticks.
  Bytes f;
  put<uint32_t>(f, 0);
  auto coord = [&](uint16_t v) { put<uint8_t>(f, 0), put<uint16_t>(f, v); };
  put<uint8_t>(f, 3), put<uint8_t>(f, 0), put<uint32_t>(f, 0), put<uint8_t>(f, 0), put<uint8_t>(f, 0), coord(0),
      put<uint8_t>(f, 1);  // ENGAGE
  put<uint8_t>(f, 1), put<uint8_t>(f, 0), put<uint32_t>(f, 0), put<uint8_t>(f, 1), put<uint32_t>(f, 1),
      put<uint8_t>(f, 0), put<uint8_t>(f, 0);
  for (uint16_t v : {400, 100, 300, 700}) put<uint8_t>(f, 0), coord(v);
  put<uint8_t>(f, 0), put<uint8_t>(f, 0), put<uint32_t>(f, 0), put<uint32_t>(f, 1), put<uint8_t>(f, 1);
  for (int i = 0; i < 3; ++i) put<uint8_t>(f, 0), coord(static_cast<uint16_t>(i == 0 ? 1300 : 1024));
  put<uint8_t>(f, 0);
  for (int i = 0; i < 20; ++i) put<uint8_t>(f, 4), put<uint8_t>(f, 0);
  write("flight", "engage-fly", f);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s TESTS_FUZZ_DIR\n", argv[0]);
    return 2;
  }
  root = argv[1];
  decode_seeds();
  image_seeds();
  mavlink_seeds();
  config_seeds(root / ".." / "..");
  stage_seeds();
  return 0;
}
