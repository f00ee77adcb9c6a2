#include "hand_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "hand_square.hpp"

namespace gpilot {

namespace {

// A user box whose part in the image is narrower or shorter than this many pixels holds no hand to find: its
// hand square (box width / 4) would be under a pixel.
constexpr int kMinBoxSidePx = 4;

// A forearm hanging at rest beside the body has its middle in the outer half of its side of the box: at least
// this many box widths from p_uc.x (each side is half a box wide).
constexpr double kOuterHalfOfSideRatio = 0.25;

// The classifier, refused when empty (before anything is sized from it).
SkinClassifier non_empty(SkinClassifier skin) {
  if (skin.empty()) throw SkinModelError("hand detector needs a skin classifier");
  return skin;
}

}  // namespace

const char* hand_kind_name(HandKind k) {
  switch (k) {
    case HandKind::Out: return "OUT";
    case HandKind::Front: return "FRONT";
    default: return "NONE";
  }
}

HandGeometry hand_geometry(const HandsParams& p, const cv::Rect2f& b, cv::Size image, const std::optional<cv::Rect2f>& face) {
  HandGeometry g;
  if (!std::isfinite(b.x) || !std::isfinite(b.y) || !std::isfinite(b.width) || !std::isfinite(b.height) || b.width <= 0 ||
      b.height <= 0)
    return g;
  const cv::Rect frame(0, 0, image.width, image.height);
  auto rect = [&](double x0, double y0, double x1, double y1) {
    const auto r = [](double v) { return static_cast<int>(std::lround(std::clamp(v, -1e7, 1e7))); };
    return cv::Rect(cv::Point(r(x0), r(y0)), cv::Point(r(x1), r(y1))) & frame;
  };
  const double x = b.x, y = b.y, w = b.width, h = b.height;
  g.box = rect(x, y, x + w, y + h);
  g.roi = rect(x - p.roi_extend_side * w, y - p.roi_extend_top * h, x + w + p.roi_extend_side * w, y + h + p.roi_extend_bottom * h);
  g.shoulder_centre = cv::Point2f(static_cast<float>(x + w / 2), static_cast<float>(y + p.shoulder_centre_ratio * h));
  g.body_centre = cv::Point2f(static_cast<float>(x + w / 2), static_cast<float>(y + p.body_centre_ratio * h));
  g.width = static_cast<float>(w);
  // Sizes taken from the box are capped at what the image holds: beyond that a larger kernel or hand square
  // changes nothing (each already spans the whole clipped search rectangle), while a hostile 1e6 px box sized
  // a kernel of gigabytes (hands stalled 5.4 s, +545 MB).
  const double image_side = std::max(image.width, image.height);
  g.open_radius = static_cast<int>(std::lround(std::min(p.skin.open_radius_ratio * w, image_side)));
  g.hand_side = hand_square_side(p.hand_square_ratio, w, image);
  const auto row = [](double v) { return static_cast<int>(std::lround(std::clamp(v, -1e7, 1e7))); };
  g.face_rows_end = row(y + p.face_remove_ratio * h);
  // The box's ratio puts the chin's row where the box's top puts it: a box 8 px (0.15 face) higher than the
  // preset's, as a re-anchor with the track's fitted ratios made it, left the whole neck in the front band, and a
  // resting user's neck was a hand in front (CLOSER for 1 s). A known face says where the neck ends.
  if (face && p.neck_in_faces > 0 && std::isfinite(face->y) && std::isfinite(face->height) && face->height > 0)
    g.face_rows_end = std::max(g.face_rows_end, row(neck_end_y(p.neck_in_faces, face->y, face->height)));
  g.legs_rows_begin = row(y + h - p.legs_remove_ratio * h);
  g.image = image;
  g.body_centre_in_view = square_in_view(g.body_centre, g.hand_side, image);
  g.valid = g.box.width >= kMinBoxSidePx && g.box.height >= kMinBoxSidePx;
  return g;
}

HandDetector::HandDetector(const HandsParams& params, SkinClassifier skin)
    : params_(params), skin_(non_empty(std::move(skin))), own_clothing_(params.skin.adapt, skin_.bins()) {}

HandResult HandDetector::detect(const cv::Mat& bgr, const cv::Rect2f& user_box, const SkinClassifier* skin,
                                 const std::optional<cv::Rect2f>& face, const ClothingColours* clothing) {
  CV_Assert(bgr.type() == CV_8UC3);
  const HandGeometry g = hand_geometry(params_, user_box, bgr.size(), face);
  last_roi_ = g.valid ? g.roi : cv::Rect();
  if (!g.valid) {
    mask_.release();
    HandResult r;
    r.geometry = g;
    return r;
  }
  const cv::Mat& arm_skin = make_skin_mask(bgr, skin ? *skin : skin_, g);
  // One labelling of the skin components serves both shape rules (the blobs dropped are gone whole, so the
  // components left keep their labels and stats).
  const bool keep_unopened = &arm_skin == &unopened_;
  const bool hanging_rule = params_.out_not_beside_hanging_forearm && params_.front_max_upright > 0;
  const int components = params_.max_blob_hand_areas > 0 || hanging_rule
                             ? cv::connectedComponentsWithStats(mask_, labels_, stats_, centroids_, 8, CV_32S)
                             : 0;
  const int dropped = drop_large_blobs(mask_, g, components, keep_unopened ? &unopened_ : nullptr);
  find_hanging_forearms(g, hanging_rule ? components : 0);
  HandResult res = run(mask_, g.roi.tl(), g);
  const int armless = out_on_an_arm(bgr, arm_skin, g, clothing, res);
  front_not_a_forearm(g, res);
  res.blobs_dropped = dropped;
  res.armless_dropped = armless;
  return res;
}

const cv::Mat& HandDetector::make_skin_mask(const cv::Mat& bgr, const SkinClassifier& skin, const HandGeometry& g) {
  skin.classify(bgr(g.roi), mask_);
  // The arm test (on_an_arm) reads the skin before the opening: a far user's arm is 2-3 px thick, and the
  // opening that clears speckles from the hand candidates cut it from the hand on some frames and not others
  // (an OUT lost for 3 s at 9.8 m).
  const bool keep_unopened = params_.arm_connected && g.open_radius > 0;
  if (keep_unopened) mask_.copyTo(unopened_);
  if (g.open_radius > 0) {
    const int side = 2 * g.open_radius + 1;
    cv::morphologyEx(mask_, mask_, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, {side, side}));
  }
  // Face/neck and legs/feet: rows of the user box (box columns only) cleared by the preset ratios.
  const cv::Rect top(g.box.x, g.box.y, g.box.width, std::max(0, g.face_rows_end - g.box.y));
  const cv::Rect bottom(g.box.x, g.legs_rows_begin, g.box.width, std::max(0, g.box.br().y - g.legs_rows_begin));
  for (const cv::Rect& r : {top & g.box, bottom & g.box})
    if (!r.empty()) {
      mask_(r - g.roi.tl()).setTo(0);
      if (keep_unopened) unopened_(r - g.roi.tl()).setTo(0);
    }
  return keep_unopened ? unopened_ : mask_;
}

int HandDetector::out_on_an_arm(const cv::Mat& bgr, const cv::Mat& arm_skin, const HandGeometry& g,
                                const ClothingColours* clothing, HandResult& res) {
  // An OUT hand hangs on an arm: its skin component goes when no path of arm-coloured pixels (skin or the user's
  // own clothing) joins it to the torso, and Alg. 1 looks again; after a few, skin outside the box goes.
  int armless = 0;
  while (res.kind == HandKind::Out && params_.arm_connected) {
    if (!clothing) own_clothing_.learn(bgr, torso_rect(params_, g)), clothing = &own_clothing_;
    if (on_an_arm(bgr, arm_skin, g, *clothing, res.hand)) break;
    if (++armless < kMaxDroppedCandidates) {
      erase_component(g, res.hand);
    } else {
      const cv::Rect box = g.box - g.roi.tl();
      cv::Mat keep = cv::Mat::zeros(mask_.size(), CV_8UC1);
      mask_(box).copyTo(keep(box));
      mask_ = keep;
    }
    res = run(mask_, g.roi.tl(), g);
  }
  return armless;
}

void HandDetector::front_not_a_forearm(const HandGeometry& g, HandResult& res) {
  // A FRONT hand is in front of the body, not a forearm hanging at the torso's edge: a skin component much
  // taller than wide that reaches below the body centre is dropped, and Alg. 2 looks again (three times).
  for (int tries = 0; res.kind == HandKind::Front && (params_.front_max_upright > 0 || params_.front_max_hand_areas > 0);
       ++tries) {
    cv::Mat copy = mask_.clone();
    cv::Rect blob;
    const int area = cv::floodFill(copy, res.hand - g.roi.tl(), cv::Scalar(2), &blob, cv::Scalar(), cv::Scalar(), 8);
    blob += g.roi.tl();
    const bool hanging = params_.front_max_upright > 0 && blob.height > params_.front_max_upright * blob.width &&
                         blob.br().y > g.body_centre.y;
    const bool torso_sized = params_.front_max_hand_areas > 0 &&
                             area > params_.front_max_hand_areas * static_cast<double>(g.hand_side) * g.hand_side;
    if (!hanging && !torso_sized) break;
    const int upright = res.upright_dropped + 1;
    if (tries + 1 >= kMaxDroppedCandidates) {
      // Given up: no hand this frame (HAND_OBS's skin counts zero, as for any NONE the rules make), but the
      // result still says how many candidates were dropped.
      res = HandResult{};
      res.geometry = g;
      res.upright_dropped = upright;
      break;
    }
    erase_component(g, res.hand);
    res = run(mask_, g.roi.tl(), g);
    res.upright_dropped = upright;
  }
}

void HandDetector::find_hanging_forearms(const HandGeometry& g, int n) {
  hanging_ = {false, false};
  // A forearm hanging at rest beside the body: a skin component much taller than wide (front_max_upright), its
  // middle inside the box in the outer half of its side, reaching below the body centre. That side's arm is down:
  // no hand of it is stretched out (a skin-coloured wall at the frame's bottom beside a resting user was an OUT
  // hand, joined to the torso through the resting forearm: a false DOWN in the closed-loop nuisances runs).
  const double outer_half = kOuterHalfOfSideRatio * g.width;
  for (int i = 1; i < n; ++i) {
    if (blob_dropped_[static_cast<size_t>(i)]) continue;
    const int* st = stats_.ptr<int>(i);
    const int x = st[cv::CC_STAT_LEFT] + g.roi.x, y = st[cv::CC_STAT_TOP] + g.roi.y;
    const int w = st[cv::CC_STAT_WIDTH], h = st[cv::CC_STAT_HEIGHT];
    const double cx = x + w / 2.0;
    if (h <= params_.front_max_upright * w || y + h <= g.body_centre.y) continue;
    if (cx < g.box.x || cx >= g.box.br().x || std::abs(cx - g.shoulder_centre.x) < outer_half) continue;
    hanging_[cx < g.shoulder_centre.x ? 0 : 1] = true;
  }
}

void HandDetector::erase_component(const HandGeometry& g, cv::Point pixel) {
  cv::floodFill(mask_, pixel - g.roi.tl(), cv::Scalar(0), nullptr, cv::Scalar(), cv::Scalar(), 8);
}

cv::Rect torso_rect(const HandsParams& p, const HandGeometry& g) {
  // Inside the (clipped) box; empty when the body centre lies above the face rows or the box's top (a box
  // mostly above the frame): cv::Rect(Point, Point) would swap the corners and reach rows above the image.
  const int inset = static_cast<int>(std::lround(p.torso_inset_ratio * g.box.width));
  const int x0 = g.box.x + inset, x1 = g.box.br().x - inset;
  const int y0 = std::max(g.box.y, g.face_rows_end), y1 = std::min(g.box.br().y, static_cast<int>(g.body_centre.y));
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

bool HandDetector::on_an_arm(const cv::Mat& bgr, const cv::Mat& skin, const HandGeometry& g,
                             const ClothingColours& clothing, cv::Point hand) {
  // Arm-coloured pixels of the search rectangle: the skin (a skin-coloured wall dropped, so it cannot join a
  // dome to the user), or a colour worn on the torso (a sleeve is the same); closed by the arm radius so a watch
  // or a shadow at the wrist does not cut the arm. Candidates erased before this one were joined to no torso, so
  // they join no other hand to it either.
  const cv::Mat roi = bgr(g.roi);
  arm_.create(roi.size(), CV_8UC1);
  for (int y = 0; y < roi.rows; ++y) {
    const uint8_t* p = roi.ptr<uint8_t>(y);
    const uint8_t* m = skin.ptr<uint8_t>(y);
    uint8_t* a = arm_.ptr<uint8_t>(y);
    for (int x = 0; x < roi.cols; ++x, p += 3) a[x] = m[x] || clothing.worn(p) ? 1 : 0;
  }
  // Capped at the search rectangle's size, as the opening radius (hand_geometry): no larger kernel differs.
  const int r = std::max(1, static_cast<int>(std::lround(std::min<double>(params_.arm_radius_ratio * g.width,
                                                                          std::max(g.roi.width, g.roi.height)))));
  cv::morphologyEx(arm_, arm_, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, {2 * r + 1, 2 * r + 1}));
  const cv::Point seed = hand - g.roi.tl();
  if (!cv::Rect(0, 0, arm_.cols, arm_.rows).contains(seed) || !arm_.at<uint8_t>(seed)) return false;
  cv::floodFill(arm_, seed, cv::Scalar(2), nullptr, cv::Scalar(), cv::Scalar(), 8);
  // Reached the torso itself, not the box's margins beside it (a skin-coloured wall there touches the box).
  const cv::Rect torso = torso_rect(params_, g) & g.roi;
  if (torso.empty()) return false;
  const cv::Mat band = arm_(torso - g.roi.tl());
  for (int y = 0; y < band.rows; ++y) {
    const uint8_t* a = band.ptr<uint8_t>(y);
    for (int x = 0; x < band.cols; ++x)
      if (a[x] == 2) return true;
  }
  return false;
}

int HandDetector::drop_large_blobs(cv::Mat& mask, const HandGeometry& g, int n, cv::Mat* also) {
  blob_dropped_.assign(static_cast<size_t>(std::max(n, 1)), 0);
  if (params_.max_blob_hand_areas <= 0 || n <= 1) return 0;
  // Measured outside the user box only: a wall or a wooden cabinet beside the user is skin-coloured there,
  // while a bare arm reaching out leaves only its forearm and hand outside (a bare torso is Alg. 2's matter).
  const double max_area = params_.max_blob_hand_areas * g.hand_side * g.hand_side;
  std::vector<int> outside(static_cast<size_t>(n), 0);
  const cv::Rect box = g.box - g.roi.tl();
  for (int y = 0; y < mask.rows; ++y) {
    const int32_t* l = labels_.ptr<int32_t>(y);
    const bool row_in = y >= box.y && y < box.br().y;
    for (int x = 0; x < mask.cols; ++x)
      if (l[x] && !(row_in && x >= box.x && x < box.br().x)) ++outside[static_cast<size_t>(l[x])];
  }
  std::vector<uint8_t>& drop = blob_dropped_;
  int dropped = 0;
  for (int i = 1; i < n; ++i)
    if (outside[static_cast<size_t>(i)] > max_area) drop[static_cast<size_t>(i)] = 1, ++dropped;
  if (!dropped) return 0;
  for (int y = 0; y < mask.rows; ++y) {
    uint8_t* m = mask.ptr<uint8_t>(y);
    uint8_t* a = also ? also->ptr<uint8_t>(y) : nullptr;
    const int32_t* l = labels_.ptr<int32_t>(y);
    for (int x = 0; x < mask.cols; ++x)
      if (drop[static_cast<size_t>(l[x])]) {
        m[x] = 0;
        if (a) a[x] = 0;
      }
  }
  return dropped;
}

HandResult HandDetector::detect_on_mask(const cv::Mat& mask, cv::Point origin, const HandGeometry& geometry) {
  CV_Assert(mask.type() == CV_8UC1);
  hanging_ = {false, false};
  cv::Mat binary = cv::min(mask, 1);
  return run(binary, origin, geometry);
}

HandResult HandDetector::run(const cv::Mat& mask, cv::Point origin, const HandGeometry& g) {
  HandResult res;
  res.geometry = g;
  if (!g.valid || mask.empty()) return res;
  cv::integral(mask, integral_, CV_32S);
  const int side = g.hand_side, half = side / 2;
  const int cols = mask.cols, rows = mask.rows;
  // F_skin at mask pixel (x, y): the side x side square [x - half, x - half + side) clipped to the mask.
  auto f_skin = [&](int x, int y) {
    const int x0 = std::max(0, x - half), x1 = std::min(cols, x - half + side);
    const int y0 = std::max(0, y - half), y1 = std::min(rows, y - half + side);
    return integral_.at<int32_t>(y1, x1) - integral_.at<int32_t>(y0, x1) - integral_.at<int32_t>(y1, x0) +
           integral_.at<int32_t>(y0, x0);
  };
  const double l1 = params_.lambda1, l2 = params_.lambda2, l3 = params_.lambda3;
  const double ucx = g.shoulder_centre.x, ucy = g.shoulder_centre.y, bcx = g.body_centre.x;
  // Alg. 1's candidates: within reach of the nearer shoulder and, below the shoulder line, at least
  // out_min_angle_deg from straight down seen from it.
  const double shoulder_dx = params_.shoulder_half_ratio * g.width;
  const double reach = params_.reach_ratio * g.width, reach2 = reach * reach;
  const double tan_min = std::tan(params_.out_min_angle_deg * M_PI / 180.0);
  // With the body centre out of the image (hips below the frame), a hand below the shoulder line whose square
  // the image border cuts is not judged: a resting hand or scenery at the cut edge, whose end is out of view.
  const bool cut_body = params_.needs_body_centre && !g.body_centre_in_view;
  auto out_candidate = [&](int ix, int iy) {
    if (hanging_[ix < ucx ? 0 : 1]) return false;
    if (cut_body && iy > ucy && square_cut_by_side_or_bottom(cv::Point2f(ix, iy), side, g.image)) return false;
    const double sx = ix < ucx ? ucx - shoulder_dx : ucx + shoulder_dx;
    const double dx = std::abs(ix - sx), dy = iy - ucy;
    if (params_.reach_ratio > 0 && dx * dx + dy * dy > reach2) return false;
    return dy <= 0 || params_.out_min_angle_deg <= 0 || dx >= tan_min * dy;
  };
  double best_out = -std::numeric_limits<double>::infinity(), best_front = best_out;
  cv::Point p_out, p_front;
  int f_out = 0, f_front = 0;
  for (int y = 0; y < rows; ++y) {
    const uint8_t* m = mask.ptr<uint8_t>(y);
    const int iy = y + origin.y;
    const bool row_in_box = iy >= g.box.y && iy < g.box.y + g.box.height;
    for (int x = 0; x < cols; ++x) {
      if (!m[x]) continue;
      const int ix = x + origin.x;
      const int f = f_skin(x, y);
      if (row_in_box && ix >= g.box.x && ix < g.box.x + g.box.width) {
        ++res.skin_inside;
        const double s = -std::abs(bcx - ix) + l3 * f;
        if (s > best_front) {
          best_front = s;
          p_front = {ix, iy};
          f_front = f;
        }
      } else if (out_candidate(ix, iy)) {
        ++res.skin_outside;
        const double s = std::abs(ucx - ix) + l2 * (ucy - iy) + l1 * f;
        if (s > best_out) {
          best_out = s;
          p_out = {ix, iy};
          f_out = f;
        }
      }
    }
  }
  res.front_candidate_skin = f_front;
  auto set = [&](HandKind kind, cv::Point p, int f, cv::Point2f ref) {
    res.kind = kind;
    res.hand = p;
    res.hand_skin = f;
    res.vector = cv::Point2f(static_cast<float>(p.x) - ref.x, static_cast<float>(p.y) - ref.y);
    res.hand_box = cv::Rect(p.x - half, p.y - half, side, side);
  };
  // The paper's pixel counts suit a user a few metres away; a far user's hand fills less of them.
  const auto min_skin = [&](int paper, double share) { return min_hand_skin(paper, share, side); };
  const double out_share = p_out.y > ucy && params_.down_min_skin_square_share > 0 ? params_.down_min_skin_square_share
                                                                                   : params_.min_skin_square_share;
  if (res.skin_outside > min_skin(params_.out_min_skin, out_share)) {
    set(HandKind::Out, p_out, f_out, g.shoulder_centre);
  } else if (res.skin_inside > 0 && std::abs(bcx - p_front.x) < params_.front_gate_ratio * g.width &&
             f_front > min_skin(params_.front_min_skin, params_.min_skin_square_share)) {
    if (cut_body) res.front_out_of_view = true;
    else set(HandKind::Front, p_front, f_front, g.body_centre);
  }
  return res;
}

}  // namespace gpilot
