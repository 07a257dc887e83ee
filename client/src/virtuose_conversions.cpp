// The C API's conversions: poses to homogeneous matrices and back, colours to grey. Pure: the
// context is not needed (VC may be NULL); errors of a NULL context go to the thread's state.
#include <Eigen/Geometry>
#include <cmath>

#include "virtuose_context.hpp"

using hapticctrl::client::virtuose::fail;

namespace {

/// A pose's quaternion may be off unit norm by float rounding; beyond this it is not a rotation.
constexpr float kQuaternionTolerance = 1e-3F;
/// How far from orthonormal (max |R^T R - I| entry) a matrix's rotation part may be.
constexpr double kRotationTolerance = 1e-3;
/// Rec. 601 luma weights.
constexpr float kRed = 0.299F;
constexpr float kGreen = 0.587F;
constexpr float kBlue = 0.114F;

using RowMajor4 = Eigen::Matrix<float, 4, 4, Eigen::RowMajor>;

}  // namespace

extern "C" {
// NOLINTBEGIN(readability-identifier-naming): VirtuoseAPI's names

int virtConvertDeplToHomogeneMatrix(VirtContext VC, float* d, float* m) {
  if (d == nullptr || m == nullptr) {
    return fail(VC, VIRT_E_INCORRECT_VALUE, "virtConvertDeplToHomogeneMatrix: NULL argument");
  }
  const Eigen::Quaternionf q(d[6], d[3], d[4], d[5]);
  if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1.0F) > kQuaternionTolerance) {
    return fail(VC, VIRT_E_INCORRECT_VALUE,
                "virtConvertDeplToHomogeneMatrix: the quaternion has not unit norm");
  }
  Eigen::Map<RowMajor4> out(m);
  out.setIdentity();
  out.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix();
  out.topRightCorner<3, 1>() << d[0], d[1], d[2];
  return 0;
}

int virtConvertHomogeneMatrixToDepl(VirtContext VC, float* d, float* m) {
  if (d == nullptr || m == nullptr) {
    return fail(VC, VIRT_E_INCORRECT_VALUE, "virtConvertHomogeneMatrixToDepl: NULL argument");
  }
  const Eigen::Map<const RowMajor4> in(m);
  const Eigen::Matrix3d r = in.topLeftCorner<3, 3>().cast<double>();
  const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!std::isfinite(off) || off > kRotationTolerance || r.determinant() < 0.0 ||
      !in.topRightCorner<3, 1>().allFinite()) {
    return fail(VC, VIRT_E_INCORRECT_VALUE,
                "virtConvertHomogeneMatrixToDepl: the 3x3 part is not a rotation");
  }
  const Eigen::Quaterniond q = Eigen::Quaterniond(r).normalized();
  d[0] = m[3];
  d[1] = m[7];
  d[2] = m[11];
  d[3] = static_cast<float>(q.x());
  d[4] = static_cast<float>(q.y());
  d[5] = static_cast<float>(q.z());
  d[6] = static_cast<float>(q.w());
  return 0;
}

int virtConvertRGBToGrayscale(VirtContext VC, float* rgb, float* gray) {
  if (rgb == nullptr || gray == nullptr) {
    return fail(VC, VIRT_E_INCORRECT_VALUE, "virtConvertRGBToGrayscale: NULL argument");
  }
  *gray = kRed * rgb[0] + kGreen * rgb[1] + kBlue * rgb[2];
  return 0;
}

// NOLINTEND(readability-identifier-naming)
}  // extern "C"
