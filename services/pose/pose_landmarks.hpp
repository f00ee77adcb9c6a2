// BlazePose's 33 body landmarks as the pose core gives them: image pixels of the whole frame. The one
// definition the pose core, the hands stage's pose method, HAND_OBS and the view share.
#pragma once

#include <array>

namespace gpilot {

struct PoseLandmark {
  float x = 0;           //!< pixels, image axes (x right)
  float y = 0;           //!< pixels, image axes (y down)
  float z = 0;           //!< depth relative to the hips' midpoint, pixels (the x scale); smaller is nearer the camera
  float visibility = 0;  //!< probability the point is visible (not occluded), 0..1
  float presence = 0;    //!< probability the point is in the frame, 0..1
};

constexpr int kPoseLandmarkCount = 33;
using PoseLandmarks = std::array<PoseLandmark, kPoseLandmarkCount>;

// BlazePose's landmark order ("left" is the person's left, which faces the camera on the image's right).
namespace pose_landmark {
enum Index : int {
  kNose = 0,
  kLeftEyeInner, kLeftEye, kLeftEyeOuter, kRightEyeInner, kRightEye, kRightEyeOuter,
  kLeftEar, kRightEar, kMouthLeft, kMouthRight,
  kLeftShoulder = 11, kRightShoulder, kLeftElbow, kRightElbow, kLeftWrist, kRightWrist,
  kLeftPinky, kRightPinky, kLeftIndex, kRightIndex, kLeftThumb, kRightThumb,
  kLeftHip = 23, kRightHip, kLeftKnee, kRightKnee, kLeftAnkle, kRightAnkle,
  kLeftHeel, kRightHeel, kLeftFootIndex, kRightFootIndex,
};

// The body's bones as drawn (MediaPipe's pose connections without the face's): pairs of landmark indices.
constexpr std::array<std::array<int, 2>, 24> kBones{{
    {kLeftShoulder, kRightShoulder}, {kLeftShoulder, kLeftHip}, {kRightShoulder, kRightHip}, {kLeftHip, kRightHip},
    {kLeftShoulder, kLeftElbow}, {kLeftElbow, kLeftWrist}, {kRightShoulder, kRightElbow}, {kRightElbow, kRightWrist},
    {kLeftWrist, kLeftPinky}, {kLeftWrist, kLeftIndex}, {kLeftPinky, kLeftIndex}, {kLeftWrist, kLeftThumb},
    {kRightWrist, kRightPinky}, {kRightWrist, kRightIndex}, {kRightPinky, kRightIndex}, {kRightWrist, kRightThumb},
    {kLeftHip, kLeftKnee}, {kLeftKnee, kLeftAnkle}, {kRightHip, kRightKnee}, {kRightKnee, kRightAnkle},
    {kLeftAnkle, kLeftHeel}, {kLeftHeel, kLeftFootIndex}, {kRightAnkle, kRightHeel}, {kRightHeel, kRightFootIndex},
}};
}  // namespace pose_landmark

}  // namespace gpilot
