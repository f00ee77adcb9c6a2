#include "person_csv.hpp"

#include <stdexcept>

namespace gpilot {

namespace {

// Quotes a field if it holds a comma or a quote.
std::string field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

std::string rect(const std::optional<cv::Rect2f>& r) {
  if (!r) return ",,,";
  return num(r->x) + "," + num(r->y) + "," + num(r->width) + "," + num(r->height);
}

std::string point(const std::optional<cv::Point2f>& p) { return p ? num(p->x) + "," + num(p->y) : ","; }

}  // namespace

PersonCsv::PersonCsv(const std::string& path) : f_(std::fopen(path.c_str(), "w")) {
  if (!f_) throw std::runtime_error("cannot write " + path);
  std::fprintf(f_,
               "image,annotation_id,box_mode,status,note,truth_left,truth_right,truth_person,"
               "box_x,box_y,box_w,box_h,face_found,face_x,face_y,face_w,face_h,"
               "stage_box_x,stage_box_y,stage_box_w,stage_box_h,stage_kind,hand_x,hand_y,p_uc_x,p_uc_y,p_bc_x,p_bc_y,vector_from,vector_x,vector_y,"
               "truth_arm,truth_vector_x,truth_vector_y,angle_error_deg,front_high_low_right,false_hand,"
               "hand_skin,skin_outside,skin_inside,truth_hand_skin,truth_hand_shows_skin,pose_score,pose_reading\n");
}

PersonCsv::~PersonCsv() {
  if (f_) std::fclose(f_);
}

void PersonCsv::write(const PersonCsvRow& r) {
  const PersonKeypointTruth* t = r.truth && r.truth->usable ? r.truth : nullptr;
  std::string line = field(r.image) + "," + std::to_string(r.annotation_id) + "," + r.box_mode + "," + r.status + "," + field(r.note) + ",";
  line += t ? std::string(arm_truth_name(t->left.label)) + "," + arm_truth_name(t->right.label) + "," + person_truth_name(t->person) + ","
            : std::string(",,,");
  line += rect(r.box) + "," + (r.face ? "1" : "0") + "," + rect(r.face) + ",";
  if (r.result) {
    const HandsOutput& h = *r.result;
    const char* from = h.kind == HandKind::Out ? "p_uc" : h.kind == HandKind::Front ? "p_bc" : "";
    const cv::Rect2f box = h.skin ? cv::Rect2f(h.skin->detection.geometry.box) : h.user_box;  // the skin method's: clipped
    line += rect(box) + "," + hand_kind_name(h.kind) + "," + point(h.hand) + "," + point(h.shoulder_centre) + "," +
            point(h.body_centre) + "," + from + "," + point(h.vector) + ",";
  } else {
    line += ",,,,,,,,,,,,,,";
  }
  if (r.score) {
    const PersonScore& s = *r.score;
    line += s.truth_arm + "," + point(s.truth_vector) + "," + (s.out_angle_error_deg ? num(*s.out_angle_error_deg) : "") + "," +
            (s.front_high_low_right ? (*s.front_high_low_right ? "1" : "0") : "") + "," + (t && t->person == PersonTruth::Rest ? (s.false_hand ? "1" : "0") : "") + ",";
  } else {
    line += ",,,,,,";
  }
  if (r.result && r.result->skin) {
    const HandResult& d = r.result->skin->detection;
    line += std::to_string(d.hand_skin) + "," + std::to_string(d.skin_outside) + "," + std::to_string(d.skin_inside);
  }
  else
    line += ",,";
  const bool measured = r.score && r.score->hand_skin;
  line += "," + (measured ? std::to_string(*r.score->hand_skin) : std::string()) + "," +
          (measured ? (r.score->hand_shows_skin ? "1" : "0") : "");
  if (r.result && r.result->pose) line += "," + num(r.result->pose->score) + "," + field(r.result->pose->reading);
  else line += ",,";
  std::fprintf(f_, "%s\n", line.c_str());
}

}  // namespace gpilot
