// A small reader of COCO person-keypoint files (the format of MS-COCO's person_keypoints_*.json):
// `images` (id, file_name, width, height [, license, flickr_url]), `annotations` (id, image_id, bbox [x,y,w,h],
// keypoints as x,y,v triples) and `categories[].keypoints` (the keypoint names). Keypoints are looked up by
// NAME through the annotation's category, never by a fixed index. Pure: no OpenCV images, no clock.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace gpilot {

// A file that is not COCO keypoints (missing or mistyped field, wrong keypoint count, unknown id): the message
// names the file and the offending entry.
class CocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CocoKeypoint {
  cv::Point2f p;  //!< pixels
  int v = 0;      //!< COCO visibility: 0 not labelled, 1 labelled but hidden, 2 labelled and visible
};

struct CocoImage {
  int64_t id = 0;
  std::string file_name;
  int width = 0, height = 0;
  int license = 0;          //!< images[].license, 0 when absent
  std::string flickr_url;   //!< "" when absent
};

struct CocoAnnotation {
  int64_t id = 0;
  int64_t image_id = 0;
  int64_t category_id = 0;
  cv::Rect2f bbox;                      //!< x, y (top-left), width, height, pixels
  std::vector<CocoKeypoint> keypoints;  //!< in the order of its category's keypoint names
};

struct CocoCategory {
  int64_t id = 0;
  std::string name;
  std::vector<std::string> keypoints;
};

class CocoKeypointFile {
 public:
  // Throws CocoError (unreadable file, not JSON, missing/mistyped fields) with the file name in the message.
  static CocoKeypointFile load(const std::string& path);
  // The same from JSON text; source names it in error messages.
  static CocoKeypointFile parse(const std::string& json_text, const std::string& source = "<json>");

  const std::vector<CocoImage>& images() const { return images_; }
  const std::vector<CocoAnnotation>& annotations() const { return annotations_; }  //!< only those with keypoints
  const std::vector<CocoCategory>& categories() const { return categories_; }

  // The image of an annotation; throws CocoError for an unknown id.
  const CocoImage& image(int64_t image_id) const;
  // Keypoint `name` of an annotation (looked up in its category's names); nullopt if the category has no such
  // keypoint name.
  std::optional<CocoKeypoint> keypoint(const CocoAnnotation& a, const std::string& name) const;

 private:
  std::vector<CocoImage> images_;
  std::vector<CocoAnnotation> annotations_;
  std::vector<CocoCategory> categories_;
  std::map<int64_t, size_t> image_index_;
  std::map<int64_t, std::map<std::string, size_t>> keypoint_index_;  //!< category id -> name -> index
};

}  // namespace gpilot
