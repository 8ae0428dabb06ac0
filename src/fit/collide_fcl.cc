/*
 * collide_fcl.cc - collide.h on FCL 0.7: the one C++ translation unit.
 * Nothing here throws past the C interface: every FCL call is wrapped.
 */
#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "fit/collide.h"

namespace {
using Model = fcl::BVHModel<fcl::OBBRSSd>;

fcl::Transform3d
to_fcl(const struct xform *x)
{
	fcl::Transform3d t = fcl::Transform3d::Identity();
	fcl::Matrix3d r;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			r(i, j) = x->r[3 * i + j];
	t.linear() = r;
	t.translation() = fcl::Vector3d(x->p[0], x->p[1], x->p[2]);
	return t;
}

void
put(double dest[3], const fcl::Vector3d &v)
{
	dest[0] = v[0];
	dest[1] = v[1];
	dest[2] = v[2];
}
} // namespace

struct collide_mesh {
	std::shared_ptr<Model> model;
	double lo[3], hi[3];
};

extern "C" struct collide_mesh *
collide_mesh_make(const float *pos, int nvert, const unsigned *idx, int ntri, char *err,
		  size_t errlen)
{
	if (nvert < 3 || ntri < 1 || !pos || !idx) {
		snprintf(err, errlen, "an empty mesh (%d vertices, %d triangles)", nvert, ntri);
		return nullptr;
	}
	try {
		std::vector<fcl::Vector3d> pts((size_t)nvert);
		double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
		for (int i = 0; i < nvert; i++) {
			for (int k = 0; k < 3; k++) {
				double v = pos[3 * i + k];
				if (!std::isfinite(v)) {
					snprintf(err, errlen, "vertex %d is not finite", i);
					return nullptr;
				}
				lo[k] = v < lo[k] ? v : lo[k];
				hi[k] = v > hi[k] ? v : hi[k];
			}
			pts[(size_t)i] = fcl::Vector3d(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
		}
		std::vector<fcl::Triangle> tris((size_t)ntri);
		for (int t = 0; t < ntri; t++) {
			for (int k = 0; k < 3; k++)
				if (idx[3 * t + k] >= (unsigned)nvert) {
					snprintf(err, errlen, "triangle %d names vertex %u of %d", t,
						 idx[3 * t + k], nvert);
					return nullptr;
				}
			tris[(size_t)t] = fcl::Triangle(idx[3 * t], idx[3 * t + 1], idx[3 * t + 2]);
		}
		std::unique_ptr<collide_mesh> m(new collide_mesh);
		m->model = std::make_shared<Model>();
		if (m->model->beginModel(ntri, nvert) != fcl::BVH_OK ||
		    m->model->addSubModel(pts, tris) != fcl::BVH_OK || m->model->endModel() != fcl::BVH_OK) {
			snprintf(err, errlen, "the bounding volume hierarchy could not be built");
			return nullptr;
		}
		for (int k = 0; k < 3; k++) {
			m->lo[k] = lo[k];
			m->hi[k] = hi[k];
		}
		return m.release();
	} catch (const std::bad_alloc &) {
		snprintf(err, errlen, "out of memory");
	} catch (...) {
		snprintf(err, errlen, "the collision library failed to build the mesh");
	}
	return nullptr;
}

extern "C" void
collide_mesh_free(struct collide_mesh *m)
{
	delete m;
}

extern "C" int
collide_mesh_triangles(const struct collide_mesh *m)
{
	return m->model->num_tris;
}

extern "C" void
collide_mesh_bounds(const struct collide_mesh *m, double lo[3], double hi[3])
{
	for (int k = 0; k < 3; k++) {
		lo[k] = m->lo[k];
		hi[k] = m->hi[k];
	}
}

struct collide_scratch {
	/* cleared, not freed, between queries: its contact list keeps its capacity */
	fcl::CollisionResultd contacts;
};

extern "C" struct collide_scratch *
collide_scratch_make(void)
{
	try {
		std::unique_ptr<collide_scratch> sc(new collide_scratch);
		fcl::Contactd c;
		for (int i = 0; i < 256; i++) /* room for the contacts of a deep overlap */
			sc->contacts.addContact(c);
		sc->contacts.clear();
		return sc.release();
	} catch (...) {
		return nullptr;
	}
}

extern "C" void
collide_scratch_free(struct collide_scratch *sc)
{
	delete sc;
}

/* the deepest contact of two overlapping meshes: 1 found, 0 none */
static int
deepest_contact(collide_scratch *sc, const fcl::CollisionObjectd &oa,
		const fcl::CollisionObjectd &ob, struct collide_result *out)
{
	fcl::CollisionRequestd req(100000, true); /* every contact, with its depth */
	fcl::CollisionResultd &res = sc->contacts;
	res.clear();
	fcl::collide(&oa, &ob, req, res);
	if (!res.isCollision() || res.numContacts() == 0)
		return 0;
	size_t deep = 0;
	for (size_t i = 1; i < res.numContacts(); i++)
		if (res.getContact(i).penetration_depth > res.getContact(deep).penetration_depth)
			deep = i;
	const fcl::Contactd &c = res.getContact(deep);
	out->distance = -c.penetration_depth;
	put(out->pa, c.pos);
	put(out->pb, c.pos);
	return 1;
}

extern "C" int
collide_distance(struct collide_scratch *sc, const struct collide_mesh *a, const struct xform *xa,
		 const struct collide_mesh *b, const struct xform *xb, struct collide_result *out)
{
	try {
		fcl::CollisionObjectd oa(a->model, to_fcl(xa)), ob(b->model, to_fcl(xb));
		fcl::DistanceRequestd req(true); /* with the nearest points */
		fcl::DistanceResultd res;
		fcl::distance(&oa, &ob, req, res);
		if (res.min_distance > 0) {
			out->distance = res.min_distance;
			put(out->pa, res.nearest_points[0]);
			put(out->pb, res.nearest_points[1]);
			return 0;
		}
		struct collide_result c;
		if (!deepest_contact(sc, oa, ob, &c)) { /* touching: no depth to report */
			out->distance = 0;
			put(out->pa, res.nearest_points[0]);
			put(out->pb, res.nearest_points[1]);
			return 0;
		}
		*out = c;
		return 0;
	} catch (...) {
		return -1;
	}
}

extern "C" int
collide_overlap(struct collide_scratch *sc, const struct collide_mesh *a, const struct xform *xa,
		const struct collide_mesh *b, const struct xform *xb)
{
	try {
		fcl::CollisionObjectd oa(a->model, to_fcl(xa)), ob(b->model, to_fcl(xb));
		fcl::CollisionRequestd req;
		fcl::CollisionResultd &res = sc->contacts;
		res.clear();
		fcl::collide(&oa, &ob, req, res);
		return res.isCollision() ? 1 : 0;
	} catch (...) {
		return 0;
	}
}
