#include "coco_keypoints.hpp"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace gpilot {

namespace {

using json = nlohmann::json;

// Field access with messages that say where: "<source>: annotations[3]: field 'bbox' is missing".
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw CocoError(source_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }
  const json& field(const json& obj, const std::string& where, const char* name) const {
    if (!obj.is_object()) fail(where, "not a JSON object");
    const auto it = obj.find(name);
    if (it == obj.end() || it->is_null()) fail(where, std::string("field '") + name + "' is missing");
    return *it;
  }
  const json& array(const json& obj, const std::string& where, const char* name) const {
    const json& a = field(obj, where, name);
    if (!a.is_array()) fail(where, std::string("field '") + name + "' is not an array");
    return a;
  }
  int64_t integer(const json& obj, const std::string& where, const char* name) const {
    const json& v = field(obj, where, name);
    if (!v.is_number_integer()) fail(where, std::string("field '") + name + "' is not an integer");
    return v.get<int64_t>();
  }
  double number(const json& v, const std::string& where, const std::string& what) const {
    if (!v.is_number()) fail(where, what + " is not a number");
    return v.get<double>();
  }
  std::string string(const json& obj, const std::string& where, const char* name) const {
    const json& v = field(obj, where, name);
    if (!v.is_string()) fail(where, std::string("field '") + name + "' is not a string");
    return v.get<std::string>();
  }

 private:
  std::string source_;
};

std::string at(const char* list, size_t i) { return std::string(list) + "[" + std::to_string(i) + "]"; }

}  // namespace

CocoKeypointFile CocoKeypointFile::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CocoError(path + ": cannot read the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

CocoKeypointFile CocoKeypointFile::parse(const std::string& json_text, const std::string& source) {
  const Reader r(source);
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    r.fail("", std::string("not JSON: ") + e.what());
  }
  CocoKeypointFile f;

  const json& cats = r.array(doc, "", "categories");
  for (size_t i = 0; i < cats.size(); ++i) {
    const std::string where = at("categories", i);
    CocoCategory c;
    c.id = r.integer(cats[i], where, "id");
    c.name = cats[i].contains("name") && cats[i]["name"].is_string() ? cats[i]["name"].get<std::string>() : "";
    if (cats[i].contains("keypoints")) {
      const json& names = r.array(cats[i], where, "keypoints");
      for (size_t k = 0; k < names.size(); ++k) {
        if (!names[k].is_string()) r.fail(where, "keypoints[" + std::to_string(k) + "] is not a string");
        c.keypoints.push_back(names[k].get<std::string>());
        f.keypoint_index_[c.id][c.keypoints.back()] = k;
      }
    }
    f.categories_.push_back(std::move(c));
  }
  if (f.keypoint_index_.empty()) r.fail("categories", "no category has a 'keypoints' list (not a person-keypoints file)");

  const json& imgs = r.array(doc, "", "images");
  for (size_t i = 0; i < imgs.size(); ++i) {
    const std::string where = at("images", i);
    CocoImage im;
    im.id = r.integer(imgs[i], where, "id");
    im.file_name = r.string(imgs[i], where, "file_name");
    im.width = static_cast<int>(r.integer(imgs[i], where, "width"));
    im.height = static_cast<int>(r.integer(imgs[i], where, "height"));
    if (imgs[i].contains("license") && imgs[i]["license"].is_number_integer()) im.license = imgs[i]["license"].get<int>();
    if (imgs[i].contains("flickr_url") && imgs[i]["flickr_url"].is_string()) im.flickr_url = imgs[i]["flickr_url"].get<std::string>();
    if (!f.image_index_.emplace(im.id, f.images_.size()).second) r.fail(where, "duplicate image id " + std::to_string(im.id));
    f.images_.push_back(std::move(im));
  }

  const json& anns = r.array(doc, "", "annotations");
  for (size_t i = 0; i < anns.size(); ++i) {
    const std::string where = at("annotations", i);
    CocoAnnotation a;
    a.id = r.integer(anns[i], where, "id");
    a.image_id = r.integer(anns[i], where, "image_id");
    a.category_id = r.integer(anns[i], where, "category_id");
    const auto cat = f.keypoint_index_.find(a.category_id);
    if (cat == f.keypoint_index_.end()) continue;  // a category without keypoints (instances file): not ours
    if (!f.image_index_.count(a.image_id)) r.fail(where, "image_id " + std::to_string(a.image_id) + " is not in 'images'");
    const json& bbox = r.array(anns[i], where, "bbox");
    if (bbox.size() != 4) r.fail(where, "bbox has " + std::to_string(bbox.size()) + " numbers, not 4 (x, y, w, h)");
    a.bbox = cv::Rect2f(static_cast<float>(r.number(bbox[0], where, "bbox[0]")), static_cast<float>(r.number(bbox[1], where, "bbox[1]")),
                        static_cast<float>(r.number(bbox[2], where, "bbox[2]")), static_cast<float>(r.number(bbox[3], where, "bbox[3]")));
    const json& kp = r.array(anns[i], where, "keypoints");
    const size_t n = cat->second.size();
    if (kp.size() != 3 * n)
      r.fail(where, "keypoints has " + std::to_string(kp.size()) + " numbers, its category names " + std::to_string(n) +
                        " keypoints (3 numbers each: x, y, v)");
    for (size_t k = 0; k < n; ++k) {
      const std::string what = "keypoints[" + std::to_string(3 * k) + "..]";
      CocoKeypoint p;
      p.p = cv::Point2f(static_cast<float>(r.number(kp[3 * k], where, what)), static_cast<float>(r.number(kp[3 * k + 1], where, what)));
      const double v = r.number(kp[3 * k + 2], where, what);
      if (v != 0 && v != 1 && v != 2) r.fail(where, what + ": visibility " + std::to_string(v) + " is not 0, 1 or 2");
      p.v = static_cast<int>(v);
      a.keypoints.push_back(p);
    }
    f.annotations_.push_back(std::move(a));
  }
  return f;
}

const CocoImage& CocoKeypointFile::image(int64_t image_id) const {
  const auto it = image_index_.find(image_id);
  if (it == image_index_.end()) throw CocoError("no image with id " + std::to_string(image_id));
  return images_[it->second];
}

std::optional<CocoKeypoint> CocoKeypointFile::keypoint(const CocoAnnotation& a, const std::string& name) const {
  const auto cat = keypoint_index_.find(a.category_id);
  if (cat == keypoint_index_.end()) return std::nullopt;
  const auto it = cat->second.find(name);
  if (it == cat->second.end() || it->second >= a.keypoints.size()) return std::nullopt;
  return a.keypoints[it->second];
}

}  // namespace gpilot
