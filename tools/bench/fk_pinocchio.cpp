// fk_pinocchio - the peer of fk_human: Pinocchio's forwardKinematics +
// centerOfMass on the same figure (exported to URDF by posture-figure and
// serialised by Pinocchio's Python bindings) and the same postures.
//
// usage: fk_pinocchio MODEL.bin Q_FILE   (Q_FILE in Pinocchio's q order)
#include <pinocchio/algorithm/center-of-mass.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/model.hpp>
#include <pinocchio/multibody.hpp>
#include <pinocchio/serialization.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <vector>

int
main(int argc, char **argv)
{
	if (argc != 3) {
		std::fprintf(stderr, "usage: fk_pinocchio MODEL.bin Q_FILE\n");
		return 2;
	}
	pinocchio::Model model;
	model.loadFromBinary(argv[1]);
	pinocchio::Data data(model);
	std::vector<Eigen::VectorXd> qs;
	std::ifstream in(argv[2]);
	for (;;) {
		Eigen::VectorXd q(model.nq);
		int d = 0;
		for (; d < model.nq && (in >> q[d]); d++)
			;
		if (d < model.nq)
			break;
		qs.push_back(q);
	}
	if (qs.empty()) {
		std::fprintf(stderr, "fk_pinocchio: no postures in %s\n", argv[2]);
		return 1;
	}
	// two measurements: joint placements + centre of mass (Pinocchio's own
	// forward pass), and with every frame placed as well, which is what fk_human does
	const int batches = 31;
	double sink = 0;
	for (int with_frames = 0; with_frames < 2; with_frames++) {
		std::vector<double> per(batches);
		for (int b = 0; b < batches; b++) {
			auto t0 = std::chrono::steady_clock::now();
			for (const auto &q : qs) {
				pinocchio::forwardKinematics(model, data, q);
				if (with_frames)
					pinocchio::updateFramePlacements(model, data);
				sink += pinocchio::centerOfMass(model, data, pinocchio::POSITION, true)[1];
			}
			std::chrono::duration<double, std::micro> dt =
				std::chrono::steady_clock::now() - t0;
			per[b] = dt.count() / qs.size();
		}
		std::sort(per.begin(), per.end());
		std::printf("BENCH fk.human.pinocchio%s us=%.3f min_us=%.3f\n",
			    with_frames ? "_frames" : "", per[batches / 2], per[0]);
	}
	std::printf("fk_pinocchio: %d joints, %d frames, nq %d; %zu postures x %d batches "
		    "(checksum %.6g)\n",
		    (int)model.njoints, (int)model.nframes, (int)model.nq, qs.size(), batches, sink);
	return 0;
}
