// ik_arm_pinocchio - the Pinocchio peer of ik_arm: the classic closed-loop
// IK of Pinocchio's documentation (examples/inverse-kinematics) on the same
// arm and the same targets.
//
// usage: ik_arm_pinocchio MODEL.bin TARGETS [DT]
//
// MODEL.bin is the standard human exported to URDF by posture-figure and
// serialised by Pinocchio's Python bindings; TARGETS is the file ik_arm
// writes (9 posture values, 9 start values, 4x4 target frame per line).
// The model is reduced to the 9 arm joints clavicle_r__0 .. wrist_r__2
// (buildReducedModel, every other joint locked at 0). From q = 0, each
// iteration takes the log6 error of frame hand_r__palm against the target
// (in the frame), the frame Jacobian (LOCAL) times Jlog6, a damped least
// squares step (damping 1e-6) and integrates it with step DT (default 1:
// the Gauss-Newton step); it stops below 1e-4 error or at 1000 iterations.
// "pinocchio_clik" leaves the limits to a check afterwards,
// "pinocchio_clik_clamped" clamps q into the limits after every step.
//
// A solve succeeds when the palm is within 1 mm and 1 degree of the target
// (recomputed from the final q) and every q is within its limits; "reached"
// counts the first two alone and limit_violations the difference. Solve
// time is the whole loop (std::chrono::steady_clock).
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/joint-configuration.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/model.hpp>
#include <pinocchio/multibody.hpp>
#include <pinocchio/serialization.hpp>
#include <pinocchio/spatial/explog.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

const char *const arm_joints[] = { "clavicle_r__0", "clavicle_r__1", "shoulder_r__0",
				   "shoulder_r__1", "shoulder_r__2", "elbow_r__0",
				   "wrist_r__0",    "wrist_r__1",    "wrist_r__2" };
const int NARM = 9;
const int WARMUP = 50;
const double EPS = 1e-4, DAMP = 1e-6;
const int IT_MAX = 1000;
const double SUCCESS_POS = 1e-3, SUCCESS_ORI = M_PI / 180;

std::vector<pinocchio::SE3>
read_targets(const char *path)
{
	std::vector<pinocchio::SE3> out;
	std::ifstream in(path);
	std::string line;
	while (std::getline(in, line)) {
		if (line.empty() || line[0] == '#')
			continue;
		std::istringstream ss(line);
		double v[34];
		int n = 0;
		while (n < 34 && (ss >> v[n]))
			n++;
		if (n != 34) {
			std::fprintf(stderr, "ik_arm_pinocchio: %s: a line with %d numbers\n", path, n);
			std::exit(1);
		}
		Eigen::Matrix3d r;
		Eigen::Vector3d p;
		for (int i = 0; i < 3; i++) {
			for (int j = 0; j < 3; j++)
				r(i, j) = v[18 + 4 * i + j];
			p[i] = v[18 + 4 * i + 3];
		}
		out.emplace_back(r, p);
	}
	return out;
}

struct tally {
	std::vector<double> us;
	int success = 0, reached = 0, violations = 0, converged = 0;
	double iters = 0;
};

void
print_tally(const char *name, tally &t, double dt)
{
	std::sort(t.us.begin(), t.us.end());
	size_t n = t.us.size();
	double median = n % 2 ? t.us[n / 2] : (t.us[n / 2 - 1] + t.us[n / 2]) / 2;
	double p95 = t.us[(size_t)std::ceil(0.95 * n) - 1];
	std::printf("BENCH ik.arm6d.%s n=%zu success=%.1f median_us=%.1f p95_us=%.1f iters=%.1f "
		    "restarts=0 limit_violations=%d reached=%.1f converged=%d dt=%g\n",
		    name, n, 100.0 * t.success / n, median, p95, t.iters / n, t.violations,
		    100.0 * t.reached / n, t.converged, dt);
}

} // namespace

int
main(int argc, char **argv)
{
	if (argc < 3 || argc > 4) {
		std::fprintf(stderr, "usage: ik_arm_pinocchio MODEL.bin TARGETS [DT]\n");
		return 2;
	}
	const double dt = argc > 3 ? std::atof(argv[3]) : 1.0;
	pinocchio::Model full;
	full.loadFromBinary(argv[1]);
	std::vector<pinocchio::JointIndex> keep, lock;
	for (const char *name : arm_joints) {
		if (!full.existJointName(name)) {
			std::fprintf(stderr, "ik_arm_pinocchio: no joint %s\n", name);
			return 1;
		}
		keep.push_back(full.getJointId(name));
	}
	for (pinocchio::JointIndex j = 1; j < (pinocchio::JointIndex)full.njoints; j++)
		if (std::find(keep.begin(), keep.end(), j) == keep.end())
			lock.push_back(j);
	pinocchio::Model model =
		pinocchio::buildReducedModel(full, lock, pinocchio::neutral(full));
	pinocchio::Data data(model);
	if (model.nq != NARM || model.nv != NARM || !model.existFrame("hand_r__palm")) {
		std::fprintf(stderr, "ik_arm_pinocchio: reduced model nq %d, or no hand_r__palm\n",
			     (int)model.nq);
		return 1;
	}
	const pinocchio::FrameIndex fid = model.getFrameId("hand_r__palm");
	std::vector<pinocchio::SE3> targets = read_targets(argv[2]);
	if (targets.empty()) {
		std::fprintf(stderr, "ik_arm_pinocchio: no targets in %s\n", argv[2]);
		return 1;
	}
	const int n = (int)targets.size();

	pinocchio::Data::Matrix6x J(6, model.nv);
	pinocchio::Data::Matrix6 Jlog, JJt;
	Eigen::VectorXd q(model.nq), v(model.nv);
	Eigen::Matrix<double, 6, 1> err;
	for (int clamped = 0; clamped < 2; clamped++) {
		tally t;
		for (int i = 0; i < n + WARMUP; i++) {
			const pinocchio::SE3 &goal = targets[i < WARMUP ? i % n : i - WARMUP];
			q = pinocchio::neutral(model);
			int it = 0, ok = 0;
			auto t0 = std::chrono::steady_clock::now();
			for (;; it++) {
				pinocchio::forwardKinematics(model, data, q);
				pinocchio::updateFramePlacement(model, data, fid);
				const pinocchio::SE3 fMd = data.oMf[fid].actInv(goal);
				err = pinocchio::log6(fMd).toVector();
				if (err.norm() < EPS) {
					ok = 1;
					break;
				}
				if (it >= IT_MAX)
					break;
				J.setZero();
				pinocchio::computeFrameJacobian(model, data, q, fid, pinocchio::LOCAL, J);
				pinocchio::Jlog6(fMd.inverse(), Jlog);
				J = -Jlog * J;
				JJt.noalias() = J * J.transpose();
				JJt.diagonal().array() += DAMP;
				v.noalias() = -J.transpose() * JJt.ldlt().solve(err);
				q = pinocchio::integrate(model, q, v * dt);
				if (clamped)
					q = q.cwiseMax(model.lowerPositionLimit)
						.cwiseMin(model.upperPositionLimit);
			}
			std::chrono::duration<double, std::micro> us =
				std::chrono::steady_clock::now() - t0;
			if (i < WARMUP)
				continue;
			// the success test, from the final q
			pinocchio::forwardKinematics(model, data, q);
			pinocchio::updateFramePlacement(model, data, fid);
			const pinocchio::SE3 &e = data.oMf[fid];
			double pos = (e.translation() - goal.translation()).norm();
			double c = ((e.rotation().transpose() * goal.rotation()).trace() - 1) / 2;
			double ang = std::acos(std::max(-1.0, std::min(1.0, c)));
			bool inside = (q.array() >= model.lowerPositionLimit.array()).all() &&
				      (q.array() <= model.upperPositionLimit.array()).all();
			bool reached = pos < SUCCESS_POS && ang < SUCCESS_ORI;
			t.us.push_back(us.count());
			t.iters += it;
			t.converged += ok;
			t.reached += reached;
			t.success += reached && inside;
			t.violations += reached && !inside;
		}
		print_tally(clamped ? "pinocchio_clik_clamped" : "pinocchio_clik", t, dt);
	}
	std::printf("ik_arm_pinocchio: reduced model nq %d (%zu joints locked), frame hand_r__palm; "
		    "%d targets; eps %g, damping %g, dt %g, at most %d iterations, no restarts\n",
		    (int)model.nq, lock.size(), n, EPS, DAMP, dt, IT_MAX);
	return 0;
}
