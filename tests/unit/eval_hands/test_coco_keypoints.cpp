// The COCO person-keypoints reader on tiny inline files: lookup by name, and clear errors for broken files.
#include <gtest/gtest.h>

#include "coco_keypoints.hpp"

namespace gpilot {
namespace {

// Keypoint names in a non-COCO order: lookups must go by name. A second category without keypoints (an
// instances file's "dog") must be ignored with its annotations.
const char* kGood = R"({
  "info": {"description": "test"},
  "images": [{"id": 7, "file_name": "a.jpg", "width": 640, "height": 480, "license": 4, "flickr_url": "http://x/a.jpg"},
             {"id": 9, "file_name": "b.jpg", "width": 320, "height": 240}],
  "annotations": [
    {"id": 100, "image_id": 7, "category_id": 1, "bbox": [10.5, 20, 30, 40.25], "keypoints": [1, 2, 2, 3, 4, 1, 0, 0, 0]},
    {"id": 101, "image_id": 9, "category_id": 1, "bbox": [1, 2, 3, 4], "keypoints": [5, 6, 2, 7, 8, 2, 9, 10, 2]},
    {"id": 102, "image_id": 9, "category_id": 18, "bbox": [1, 2, 3, 4]}
  ],
  "categories": [{"id": 1, "name": "person", "keypoints": ["left_wrist", "nose", "right_hip"]},
                 {"id": 18, "name": "dog"}]
})";

TEST(CocoKeypoints, GivenASmallFileWhenParsedThenImagesAnnotationsAndKeypointsByName) {
  const CocoKeypointFile f = CocoKeypointFile::parse(kGood);
  ASSERT_EQ(f.images().size(), 2u);
  EXPECT_EQ(f.images()[0].file_name, "a.jpg");
  EXPECT_EQ(f.images()[0].width, 640);
  EXPECT_EQ(f.images()[0].license, 4);
  EXPECT_EQ(f.images()[0].flickr_url, "http://x/a.jpg");
  EXPECT_EQ(f.images()[1].license, 0);
  ASSERT_EQ(f.annotations().size(), 2u);  // the dog is not a keypoint annotation
  const CocoAnnotation& a = f.annotations()[0];
  EXPECT_EQ(a.id, 100);
  EXPECT_EQ(f.image(a.image_id).file_name, "a.jpg");
  EXPECT_FLOAT_EQ(a.bbox.x, 10.5f);
  EXPECT_FLOAT_EQ(a.bbox.height, 40.25f);
  const auto nose = f.keypoint(a, "nose");
  ASSERT_TRUE(nose.has_value());
  EXPECT_EQ(nose->p, cv::Point2f(3, 4));
  EXPECT_EQ(nose->v, 1);
  EXPECT_EQ(f.keypoint(a, "left_wrist")->p, cv::Point2f(1, 2));
  EXPECT_EQ(f.keypoint(a, "right_hip")->v, 0);
  EXPECT_FALSE(f.keypoint(a, "left_knee").has_value());
  EXPECT_EQ(f.keypoint(f.annotations()[1], "right_hip")->p, cv::Point2f(9, 10));
  EXPECT_THROW(f.image(8), CocoError);
}

// The error message of parsing text, or "" if it parsed.
std::string error_of(const std::string& text) {
  try {
    CocoKeypointFile::parse(text, "t.json");
  } catch (const CocoError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(CocoKeypoints, GivenBrokenFilesWhenParsedThenACocoErrorNamingTheProblem) {
  EXPECT_NE(error_of("{").find("t.json: not JSON"), std::string::npos) << error_of("{");
  EXPECT_NE(error_of("[]").find("not a JSON object"), std::string::npos);
  const std::string no_images = replaced(kGood, "\"images\"", "\"imgs\"");
  EXPECT_NE(error_of(no_images).find("field 'images' is missing"), std::string::npos) << error_of(no_images);
  const std::string no_bbox = replaced(kGood, "\"bbox\": [10.5, 20, 30, 40.25], ", "");
  EXPECT_NE(error_of(no_bbox).find("annotations[0]: field 'bbox' is missing"), std::string::npos) << error_of(no_bbox);
  const std::string short_bbox = replaced(kGood, "[10.5, 20, 30, 40.25]", "[10.5, 20, 30]");
  EXPECT_NE(error_of(short_bbox).find("bbox has 3 numbers"), std::string::npos) << error_of(short_bbox);
  const std::string short_kp = replaced(kGood, "[1, 2, 2, 3, 4, 1, 0, 0, 0]", "[1, 2, 2, 3, 4, 1]");
  EXPECT_NE(error_of(short_kp).find("keypoints has 6 numbers"), std::string::npos) << error_of(short_kp);
  const std::string text_kp = replaced(kGood, "[1, 2, 2, 3, 4, 1, 0, 0, 0]", "[1, \"2\", 2, 3, 4, 1, 0, 0, 0]");
  EXPECT_NE(error_of(text_kp).find("is not a number"), std::string::npos) << error_of(text_kp);
  const std::string bad_v = replaced(kGood, "[1, 2, 2, 3, 4, 1, 0, 0, 0]", "[1, 2, 3, 3, 4, 1, 0, 0, 0]");
  EXPECT_NE(error_of(bad_v).find("visibility"), std::string::npos) << error_of(bad_v);
  const std::string bad_image = replaced(kGood, "\"image_id\": 7", "\"image_id\": 8");
  EXPECT_NE(error_of(bad_image).find("image_id 8 is not in 'images'"), std::string::npos) << error_of(bad_image);
  const std::string no_name = replaced(kGood, "\"file_name\": \"a.jpg\", ", "");
  EXPECT_NE(error_of(no_name).find("images[0]: field 'file_name' is missing"), std::string::npos) << error_of(no_name);
  const std::string no_kp_names = replaced(kGood, ", \"keypoints\": [\"left_wrist\", \"nose\", \"right_hip\"]", "");
  EXPECT_NE(error_of(no_kp_names).find("not a person-keypoints file"), std::string::npos) << error_of(no_kp_names);
  const std::string no_kp = replaced(kGood, ", \"keypoints\": [5, 6, 2, 7, 8, 2, 9, 10, 2]", "");
  EXPECT_NE(error_of(no_kp).find("annotations[1]: field 'keypoints' is missing"), std::string::npos) << error_of(no_kp);
}

TEST(CocoKeypoints, GivenAMissingFileWhenLoadedThenACocoErrorWithItsName) {
  try {
    CocoKeypointFile::load("/nonexistent/annotations.json");
    FAIL() << "no error";
  } catch (const CocoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/annotations.json: cannot read"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gpilot
