// Tests of arm_dynamics.hpp: kinematics and rigid-body dynamics of the 6R chain with fixed-size
// Eigen types only.
#include "hapticctrl/rt_core/arm_dynamics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>

namespace hapticctrl::rt_core {
namespace {

const Vector6d kReady = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();

class ArmDynamicsTest : public ::testing::Test {
 protected:
  ArmDynamics dynamics_{load_arm_model(default_arm_model_path())};
  ChainState at(const Vector6d& q) {
    ChainState s;
    dynamics_.forward_kinematics(q, s);
    return s;
  }
};

TEST_F(ArmDynamicsTest, HandlePositionAtReadyPoseMatchesKdl) {
  const ChainState s = at(kReady);
  EXPECT_NEAR(s.handle_position.x(), 0.628, 5e-4);  // ARM_REFERENCE [M]
  EXPECT_NEAR(s.handle_position.y(), 0.0, 1e-9);
  EXPECT_NEAR(s.handle_position.z(), 0.227, 5e-4);
}

TEST_F(ArmDynamicsTest, JacobianTransposeMatchesKdlExample) {
  const ChainState s = at(kReady);
  Vector6d wrench;
  wrench << 0, 0, -10, 1, 0, 0;  // 10 N down + 1 N·m about x
  const Vector6d tau = dynamics_.jacobian(s).transpose() * wrench;
  const Vector6d expected = (Vector6d() << 0, 6.28, 3.81, 0.83, 1.00, 1.00).finished();  // [M]
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(tau(i), expected(i), 0.006) << "joint " << i + 1;
  }
}

TEST_F(ArmDynamicsTest, JacobianMatchesFiniteDifferenceOfKinematics) {
  const Vector6d q = (Vector6d() << 0.3, -0.4, 1.0, 0.5, -0.3, 0.7).finished();
  const ChainState s = at(q);
  const Matrix6d jac = dynamics_.jacobian(s);
  const double h = 1e-7;
  for (int i = 0; i < 6; ++i) {
    const ChainState t = at(q + h * Vector6d::Unit(i));
    const Vector3d dp = (t.handle_position - s.handle_position) / h;
    EXPECT_NEAR((dp - jac.block<3, 1>(0, i)).norm(), 0.0, 1e-5) << "column " << i;
  }
}

TEST_F(ArmDynamicsTest, GravityTorqueAtReadyPose) {
  const Vector6d g = dynamics_.gravity_torque(at(kReady));
  // Slender rods of the stated masses (see the model file about ARM_REFERENCE's [M] figures).
  EXPECT_NEAR(g(0), 0.0, 1e-9);
  EXPECT_NEAR(g(1), -3.806, 0.002);
  EXPECT_NEAR(g(2), -1.377, 0.002);
  EXPECT_NEAR(g(3), 0.0, 1e-9);
  EXPECT_NEAR(g(4), -0.084, 0.002);
}

TEST_F(ArmDynamicsTest, GravityTorqueIsTheGradientOfPotentialEnergy) {
  const Vector6d q = (Vector6d() << 0.2, -0.8, 1.4, 0.3, 0.5, -0.2).finished();
  const Vector6d g = dynamics_.gravity_torque(at(q));
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    const double dv = (dynamics_.potential_energy(at(q + h * Vector6d::Unit(i))) -
                       dynamics_.potential_energy(at(q - h * Vector6d::Unit(i)))) /
                      (2 * h);
    EXPECT_NEAR(g(i), dv, 1e-5) << "joint " << i + 1;
  }
}

TEST_F(ArmDynamicsTest, TheShippedArmCanHoldItselfAgainstGravityAndAWeakOneCannot) {
  // H3: a model can validate and still be unable to carry its own weight; the core refuses it.
  const GravityDemand shipped = gravity_demand(dynamics_);
  std::printf("the shipped arm needs up to %.1f %% of joint %d's peak torque against gravity\n",
              shipped.share * 100.0, shipped.joint + 1);
  EXPECT_GT(shipped.share, 0.01);
  EXPECT_LT(shipped.share, 1.0) << "joint " << shipped.joint + 1;
  ArmModel weak = dynamics_.model();
  weak.joints[1].torque_peak = 0.2;  // J2 carries the upper arm, forearm and wrist
  const GravityDemand demand = gravity_demand(ArmDynamics(weak));
  EXPECT_GT(demand.share, 1.0);
  EXPECT_EQ(demand.joint, 1);
}

TEST_F(ArmDynamicsTest, MassMatrixIsSymmetricPositiveDefinite) {
  const Matrix6d inertia_matrix = dynamics_.mass_matrix(at(kReady));
  EXPECT_LT((inertia_matrix - inertia_matrix.transpose()).norm(), 1e-12);
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(inertia_matrix);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

TEST_F(ArmDynamicsTest, MassMatrixColumnsAreTheTorquesOfUnitJointAccelerations) {
  for (const Vector6d& q : {kReady, (Vector6d() << 0.2, -0.8, 1.4, 0.3, 0.5, -0.2).finished(),
                            (Vector6d() << -1.0, 0.4, -0.3, 2.0, -1.1, 2.5).finished()}) {
    const ChainState chain = at(q);
    const Matrix6d inertia_matrix = dynamics_.mass_matrix(chain);
    for (int c = 0; c < 6; ++c) {
      const Vector6d column =
          dynamics_.inverse_dynamics(chain, Vector6d::Zero(), Vector6d::Unit(c), Vector3d::Zero());
      EXPECT_LT((inertia_matrix.col(c) - column).norm(), 1e-12)
          << "column " << c << " at " << q.transpose();
    }
  }
}

}  // namespace
}  // namespace hapticctrl::rt_core
