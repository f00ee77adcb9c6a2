#include "hands_score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hand_square.hpp"

namespace gpilot {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(std::ceil(p * static_cast<double>(v.size())) - 1))];
}

namespace {

double ratio(int64_t a, int64_t b) { return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0; }

}  // namespace

double angle_between_deg(cv::Point2f a, cv::Point2f b) {
  if ((a.x == 0 && a.y == 0) || (b.x == 0 && b.y == 0)) return 0;
  const double d = std::atan2(a.y, a.x) - std::atan2(b.y, b.x);
  return std::abs(std::remainder(d, 2 * M_PI)) * 180.0 / M_PI;
}

cv::Rect truth_hand_square(const ArmKeypointTruth& arm, int side) {
  const cv::Point2f c = arm.wrist + (arm.wrist - arm.elbow) * (1.0f / 3.0f);
  return {static_cast<int>(std::lround(c.x)) - side / 2, static_cast<int>(std::lround(c.y)) - side / 2, side, side};
}

namespace {

// Skin pixels (the classifier's, no opening) in the truth hand's square, clipped to the image.
int skin_in_square(const cv::Mat& bgr, const SkinClassifier& skin, const cv::Rect& square) {
  const cv::Rect r = square & cv::Rect(0, 0, bgr.cols, bgr.rows);
  if (r.empty()) return 0;
  cv::Mat mask;
  skin.classify(bgr(r), mask);
  return cv::countNonZero(mask);
}

}  // namespace

PersonScore score_person(const PersonKeypointTruth& t, const HandsOutput& r, const cv::Mat& bgr, const SkinClassifier* skin,
                         const HandsParams* params) {
  PersonScore s;
  if (!t.usable || t.person == PersonTruth::Ambiguous) return s;
  s.scored = true;
  s.expected = t.person == PersonTruth::Out ? HandKind::Out : t.person == PersonTruth::Front ? HandKind::Front : HandKind::None;
  s.kind_right = r.kind == s.expected;
  const std::pair<const char*, const ArmKeypointTruth*> arms[] = {{"left", &t.left}, {"right", &t.right}};
  if (t.person == PersonTruth::Out) {
    const cv::Point2f from = r.shoulder_centre;
    for (const auto& [side, arm] : arms) {
      if (arm->label != ArmTruth::Out) continue;
      const cv::Point2f tv = arm->wrist - from;
      const double err = angle_between_deg(r.vector, tv);
      if (!s.truth_vector || (r.kind == HandKind::Out && err < *s.out_angle_error_deg)) {
        s.truth_vector = tv;
        s.truth_arm = side;
        s.out_angle_error_deg = err;
      }
    }
    s.out_found = r.kind == HandKind::Out;
    if (!s.out_found) s.out_angle_error_deg.reset();
  } else if (t.person == PersonTruth::Front) {
    const cv::Point2f from = r.body_centre;
    const ArmKeypointTruth* best = nullptr;
    double best_d = 0;
    for (const auto& [side, arm] : arms) {
      if (!is_front(arm->label)) continue;
      const double d = cv::norm(arm->wrist - r.hand);
      if (!best || d < best_d) {
        best = arm;
        best_d = d;
        s.truth_arm = side;
      }
    }
    s.truth_vector = best->wrist - from;
    s.front_found = r.kind == HandKind::Front;
    if (s.front_found) s.front_high_low_right = (r.vector.y < 0) == (best->label == ArmTruth::FrontHigh);
  } else {
    s.false_hand = r.kind != HandKind::None;
  }
  if (skin && params && !bgr.empty() && s.expected != HandKind::None && r.user_box.width > 0) {
    // The stage's own measures for this box: its hand square and the skin count Alg. 1 / 2 ask for there.
    const int side = hand_square_side(params->hand_square_ratio, r.user_box.width, bgr.size());
    const int paper = s.expected == HandKind::Out ? params->out_min_skin : params->front_min_skin;
    const int need = min_hand_skin(paper, params->min_skin_square_share, side);
    for (const ArmKeypointTruth* arm : {&t.left, &t.right}) {
      const bool of_kind = s.expected == HandKind::Out ? arm->label == ArmTruth::Out : is_front(arm->label);
      if (!of_kind) continue;
      const int n = !r.refused.empty() ? 0 : skin_in_square(bgr, *skin, truth_hand_square(*arm, side));
      s.hand_skin = std::max(s.hand_skin.value_or(0), n);
    }
    s.hand_shows_skin = s.hand_skin.value_or(0) > need;
  }
  return s;
}

void HandsScoreboard::add_truth(const PersonKeypointTruth& t) {
  ++persons_[static_cast<int>(t.person)];
  ++arms_[static_cast<int>(t.left.label)];
  ++arms_[static_cast<int>(t.right.label)];
}

void HandsScoreboard::add_run(const PersonKeypointTruth& t, const HandsOutput& r, const PersonScore& s) {
  ++run_;
  ++run_by_truth_[static_cast<int>(t.person)];
  colourless_[static_cast<int>(t.person)] += !r.refused.empty();
  if (!s.scored) return;
  ++scored_;
  ++confusion_[static_cast<int>(s.expected)][static_cast<int>(r.kind)];
  kind_right_ += s.kind_right;
  out_found_ += s.out_found;
  if (s.out_angle_error_deg) out_angle_err_.push_back(*s.out_angle_error_deg);
  front_found_ += s.front_found;
  front_hl_right_ += s.front_high_low_right.value_or(false);
  false_hand_ += s.false_hand;
  skin_measured_ += s.hand_skin.has_value();
  if (s.hand_shows_skin && s.expected == HandKind::Out) ++out_skin_, out_skin_found_ += s.out_found;
  if (s.hand_shows_skin && s.expected == HandKind::Front) ++front_skin_, front_skin_found_ += s.front_found;
}

double HandsScoreboard::kind_accuracy() const { return ratio(kind_right_, scored_); }

nlohmann::json HandsScoreboard::to_json(const nlohmann::json& context) const {
  using nlohmann::json;
  json j = context;
  json by_truth = json::object(), run_truth = json::object(), no_face = json::object(), arms = json::object(),
       colourless = json::object();
  for (int k = 0; k < kPersonTruths; ++k) {
    const char* n = person_truth_name(static_cast<PersonTruth>(k));
    by_truth[n] = persons_[k];
    run_truth[n] = run_by_truth_[k];
    no_face[n] = no_face_[k];
    colourless[n] = colourless_[k];
  }
  for (int k = 0; k < kArmTruths; ++k) arms[arm_truth_name(static_cast<ArmTruth>(k))] = arms_[k];
  int64_t usable = 0, no_face_total = 0;
  for (int k = 0; k < kPersonTruths; ++k) {
    usable += persons_[k];
    no_face_total += no_face_[k];
  }
  j["persons_read"] = read_;
  j["skipped_not_visible"] = skipped_not_visible_;
  j["image_unreadable"] = image_unreadable_;
  j["persons_usable"] = usable;
  j["persons_by_truth"] = by_truth;
  j["arms_by_truth"] = arms;
  j["faces_found"] = faces_found_;
  j["no_face"] = no_face_total;
  j["no_face_by_truth"] = no_face;
  j["persons_run"] = run_;
  j["persons_run_by_truth"] = run_truth;
  j["colourless_by_truth"] = colourless;  // run, refused by the stage (no colour in the photo), scored as NONE
  j["ambiguous_not_scored"] = run_by_truth_[static_cast<int>(PersonTruth::Ambiguous)];
  j["persons_scored"] = scored_;
  json counts = json::array();
  for (int k = 0; k < 3; ++k) counts.push_back({confusion_[k][0], confusion_[k][1], confusion_[k][2]});
  j["confusion"] = {{"rows", "truth (expected kind)"}, {"cols", "stage kind"}, {"order", {"NONE", "OUT", "FRONT"}}, {"counts", counts}};
  j["kind_accuracy"] = kind_accuracy();
  const int64_t out_n = run_by_truth_[static_cast<int>(PersonTruth::Out)];
  const int64_t front_n = run_by_truth_[static_cast<int>(PersonTruth::Front)];
  const int64_t rest_n = run_by_truth_[static_cast<int>(PersonTruth::Rest)];
  j["out"] = {{"persons", out_n},
              {"found", out_found_},
              {"found_rate", ratio(out_found_, out_n)},
              {"vectors", "stage: hand - p_uc (stage's shoulder centre); truth: OUT wrist - the same p_uc"},
              {"angle_error_deg", {{"n", out_angle_err_.size()},
                                   {"median", median(out_angle_err_)},
                                   {"p90", percentile(out_angle_err_, 0.9)},
                                   {"max", percentile(out_angle_err_, 1.0)}}}};
  j["front"] = {{"persons", front_n},
                {"found", front_found_},
                {"found_rate", ratio(front_found_, front_n)},
                {"vectors", "stage: hand - p_bc (stage's body centre); truth HIGH/LOW: wrist above/below the torso centre"},
                {"high_low_right", front_hl_right_},
                {"high_low_right_given_found", ratio(front_hl_right_, front_found_)}};
  j["hand_shows_skin"] = {{"what", "OUT/FRONT persons whose truth hand square holds more skin (the stage's classifier) than the stage needs"},
                          {"measured", skin_measured_},
                          {"out", out_skin_},
                          {"out_found", out_skin_found_},
                          {"front", front_skin_},
                          {"front_found", front_skin_found_}};
  j["rest"] = {{"persons", rest_n}, {"false_hand", false_hand_}, {"false_hand_rate", ratio(false_hand_, rest_n)}};
  return j;
}

void HandsScoreboard::print_table(std::FILE* out, const std::string& title) const {
  int64_t usable = 0, no_face_total = 0;
  for (int k = 0; k < kPersonTruths; ++k) {
    usable += persons_[k];
    no_face_total += no_face_[k];
  }
  std::fprintf(out, "%s\n\n", title.c_str());
  std::fprintf(out, "persons read                %lld\n", static_cast<long long>(read_));
  std::fprintf(out, "skipped (v < 2 on an arm/hip keypoint) %lld, image unreadable %lld\n", static_cast<long long>(skipped_not_visible_),
               static_cast<long long>(image_unreadable_));
  std::fprintf(out, "usable persons by truth     ");
  for (int k = 0; k < kPersonTruths; ++k)
    std::fprintf(out, "%s %lld  ", person_truth_name(static_cast<PersonTruth>(k)), static_cast<long long>(persons_[k]));
  std::fprintf(out, "(%lld)\narms by truth               ", static_cast<long long>(usable));
  for (int k = 0; k < kArmTruths; ++k)
    std::fprintf(out, "%s %lld  ", arm_truth_name(static_cast<ArmTruth>(k)), static_cast<long long>(arms_[k]));
  std::fprintf(out, "\nfaces found (Haar)          %lld; no face (not run) %lld", static_cast<long long>(faces_found_),
               static_cast<long long>(no_face_total));
  if (no_face_total) {
    std::fprintf(out, " (");
    for (int k = 0; k < kPersonTruths; ++k)
      std::fprintf(out, "%s%s %lld", k ? ", " : "", person_truth_name(static_cast<PersonTruth>(k)), static_cast<long long>(no_face_[k]));
    std::fprintf(out, ")");
  }
  std::fprintf(out, "\nstage run on                %lld persons; AMBIGUOUS (not scored) %lld; scored %lld\n",
               static_cast<long long>(run_), static_cast<long long>(run_by_truth_[static_cast<int>(PersonTruth::Ambiguous)]),
               static_cast<long long>(scored_));
  std::fprintf(out, "in photos without colour    ");
  for (int k = 0; k < kPersonTruths; ++k)
    std::fprintf(out, "%s%s %lld", k ? ", " : "", person_truth_name(static_cast<PersonTruth>(k)), static_cast<long long>(colourless_[k]));
  std::fprintf(out, " (the stage refuses them: no skin colour; scored as NONE)\n\n");
  std::fprintf(out, "confusion (rows truth as expected kind, columns stage kind)\n%8s %8s %8s %8s\n", "", "NONE", "OUT", "FRONT");
  const char* rows[3] = {"REST", "OUT", "FRONT"};
  for (int k = 0; k < 3; ++k)
    std::fprintf(out, "%8s %8lld %8lld %8lld\n", rows[k], static_cast<long long>(confusion_[k][0]), static_cast<long long>(confusion_[k][1]),
                 static_cast<long long>(confusion_[k][2]));
  const int64_t out_n = run_by_truth_[static_cast<int>(PersonTruth::Out)];
  const int64_t front_n = run_by_truth_[static_cast<int>(PersonTruth::Front)];
  const int64_t rest_n = run_by_truth_[static_cast<int>(PersonTruth::Rest)];
  std::fprintf(out, "\nkind accuracy               %.1f %% of %lld scored persons\n", 100 * kind_accuracy(), static_cast<long long>(scored_));
  std::fprintf(out, "OUT found                   %lld of %lld (%.1f %%)\n", static_cast<long long>(out_found_), static_cast<long long>(out_n),
               100 * ratio(out_found_, out_n));
  std::fprintf(out, "OUT angle error             median %.1f deg, p90 %.1f, max %.1f (%zu persons; stage hand - p_uc vs truth wrist - p_uc,\n"
                    "                            p_uc = the stage's own shoulder centre)\n",
               median(out_angle_err_), percentile(out_angle_err_, 0.9), percentile(out_angle_err_, 1.0), out_angle_err_.size());
  std::fprintf(out, "FRONT found                 %lld of %lld (%.1f %%)\n", static_cast<long long>(front_found_),
               static_cast<long long>(front_n), 100 * ratio(front_found_, front_n));
  std::fprintf(out, "FRONT HIGH/LOW right        %lld of %lld found (%.1f %%; stage hand - p_bc, p_bc = stage's body centre, vs truth\n"
                    "                            wrist above/below the torso centre)\n",
               static_cast<long long>(front_hl_right_), static_cast<long long>(front_found_), 100 * ratio(front_hl_right_, front_found_));
  std::fprintf(out, "false hand on REST persons  %lld of %lld (%.1f %%)\n", static_cast<long long>(false_hand_), static_cast<long long>(rest_n),
               100 * ratio(false_hand_, rest_n));
  if (skin_measured_ == 0) {
    std::fprintf(out, "truth hand shows skin       not measured (the method judges no skin colour)\n");
    return;
  }
  std::fprintf(out, "truth hand shows skin       OUT %lld of %lld (found %lld of them), FRONT %lld of %lld (found %lld of them)\n"
                    "                            (the stage's skin, before the opening, in its hand square a third of the forearm\n"
                    "                            beyond the truth wrist, more than the stage needs: what skin colour can find)\n",
               static_cast<long long>(out_skin_), static_cast<long long>(out_n), static_cast<long long>(out_skin_found_),
               static_cast<long long>(front_skin_), static_cast<long long>(front_n), static_cast<long long>(front_skin_found_));
}

}  // namespace gpilot
