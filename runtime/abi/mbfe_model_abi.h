/* The binary interface between a generated solver and the runtime.
 *
 * Every generated model defines `const mbfe_model_v1* mbfe_model_<name>(void)`
 * with C linkage; a solver compiled at run time into a shared library also
 * defines `mbfe_model_entry` (the generated file does so when
 * MBFE_SHARED_ENTRY is defined). Plain C so that the loader needs no C++ ABI
 * agreement beyond the compiler that built both sides.
 *
 * Matrices are dense row-major; vectors have one entry per generalized
 * coordinate of the rigid part, in model (file) order.
 *
 * Planar models (dimension 2) have one position and one velocity coordinate
 * per body, q' = v. Spatial models (dimension 3) have nq position
 * coordinates q and nv velocity coordinates v, which differ when a joint has
 * a quaternion (docs/model-format.md, "Spatial models"): a spherical joint
 * has 4 entries in q, its unit quaternion (w, x, y, z), and 3 in v, its
 * angular velocity relative to its joint frame in the body frame; a free
 * joint has 7 in q (x, y, z, then the quaternion) and 6 in v (the rates of
 * x, y, z, then the angular velocity). Wherever the fields below say "qd"
 * a spatial model reads v: M is nv x nv and F, Q have nv entries. Every
 * kernel reads a quaternion as unit (the rotation matrix is written for
 * |q| = 1); normalising it after a step is the integrator's job.
 *
 * Fields are only ever appended to mbfe_model_v1: a generated solver fills
 * the struct by aggregate initialisation up to the last field it needs, and
 * the fields after it are zero, which every appended field reads as absent
 * (planar, nv = nq, no loops). A planar model without loops therefore
 * generates the same source as under version 3.
 */
#ifndef MBFE_MODEL_ABI_H_
#define MBFE_MODEL_ABI_H_

#ifdef __cplusplus
extern "C" {
#endif

#define MBFE_MODEL_ABI_VERSION 4

/* Contact kernels, one set per contact, evaluated on one beam element.
 * Inputs: q, qd (rigid coordinates); the element's 4 local beam DOFs
 * (w1, w1', w2, w2') and their rates; the element's start coordinate s0 and
 * length le. Outputs written for `rows` constraint rows (2 pin, 1 slider). */
typedef struct mbfe_contact_kernels_v1 {
  const char* name;
  int type; /* 0 = pin, 1 = slider_pin, 2 = slider_spring (a penalty force,
              not a constraint: Phi = delta = w(s) - y_P, the penetration) */
  int beam; /* index of the beam in model order */
  double at; /* pin position along the beam (m); unused for sliders */
  int rows;
  /* Position along the beam of the contact point, s(q) (slider) or `at`. */
  double (*position)(const double* q);
  /* Phi[rows] */
  void (*phi)(const double* q, const double* qe, double s0, double le, double* Phi);
  /* Jb[rows * nq] row-major, Je[rows * 4] row-major */
  void (*jacobians)(const double* q, const double* qe, double s0, double le, double* Jb,
                    double* Je);
  /* gamma[rows] = -(dJ/dt) q' */
  void (*gamma)(const double* q, const double* qd, const double* qe, const double* qed,
                double s0, double le, double* gamma);
  /* slider_spring only: N = stiffness delta + damping delta' (N/m, N s/m);
   * unilateral != 0: compression only (N = 0 when delta <= 0 or N < 0). */
  double stiffness;
  double damping;
  int unilateral;
  /* slider_spring only: 0 the point presses the beam from the side w points
   * away from (a wheel on a deck: delta = w(s) - y_P); 1 from the side w points
   * to (a pantograph under a contact wire: delta = y_P - w(s)). */
  int from_below;
} mbfe_contact_kernels_v1;

/* One closed-loop constraint (`constraints:` of the model file): its rows are
 * rows first_row .. first_row + rows - 1 of the loop kernels. */
typedef struct mbfe_loop_constraint_v1 {
  const char* name;
  int type;      /* 0 = point, 1 = revolute, 2 = prismatic */
  int first_row;
  int rows;      /* point: 3 in space, 2 in the plane; revolute, prismatic: 5 in space, 2 in the plane */
} mbfe_loop_constraint_v1;

typedef struct mbfe_model_v1 {
  int abi_version;               /* MBFE_MODEL_ABI_VERSION */
  const char* model_name;
  const char* model_sha256;      /* of the model file's bytes */
  const char* generator_version;
  int num_coordinates;           /* nq, one per rigid body */
  const char* const* coordinate_names;
  /* M[nq * nq], row-major, symmetric */
  void (*mass_matrix)(const double* q, double* M);
  /* F[nq]: velocity-dependent inertial terms */
  void (*inertial_forces)(const double* q, const double* qd, double* F);
  /* Q[nq]: gravity, loads and springs */
  void (*generalized_forces)(const double* q, const double* qd, double t, double* Q);
  /* Position (ground frame) of a named point: body index, point index. */
  void (*point_position)(const double* q, int body, int point, double* xy);
  int num_contacts;
  const mbfe_contact_kernels_v1* contacts;
  /* M, F and Q in one call, sharing the kinematics (what an integrator wants
   * at every step); may be NULL in hand-written models, then call the three
   * kernels above. */
  void (*dynamics)(const double* q, const double* qd, double t, double* M, double* F, double* Q);
  /* Driven joints (`motion:`): their coordinates (model order) and q, q', q''
   * of each at time t, in that order. 0 / NULL / NULL when none. */
  int num_driven;
  const int* driven_coordinates;
  void (*motion)(double t, double* q, double* qd, double* qdd);
  /* Tangents of tau = M(q) qdd + F(q, qd) - Q(q, qd, t) for implicit
   * integrators: K[nq * nq] = d tau / dq, C[nq * nq] = d tau / dqd, row-major,
   * at the given qdd. May be NULL in hand-written models (the runtime then
   * takes differences). */
  void (*dynamics_jacobians)(const double* q, const double* qd, const double* qdd, double t, double* K,
                             double* C);

  /* ---- Appended in ABI version 4: spatial models and closed loops. ---- */

  /* 0 or 2: planar; 3: spatial. */
  int dimension;
  /* nv, the number of velocity coordinates; 0 means nv = nq
   * (num_coordinates). M is nv x nv; F, Q, the velocity and acceleration
   * vectors have nv entries. */
  int num_velocities;
  /* nv names (<body>, or <body>_vx, _vy, _vz, _wx, _wy, _wz); NULL means
   * coordinate_names. */
  const char* const* velocity_names;
  /* qdot[nq] = G(q) v[nv], the rates of the position coordinates (m/s,
   * rad/s, 1/s for a quaternion): v itself for revolute and prismatic
   * joints and a free joint's x, y, z, and 1/2 quat * (0, w) (Hamilton's
   * product) for a quaternion. NULL means qdot = v. */
  void (*position_derivative)(const double* q, const double* v, double* qdot);
  /* For a driven joint (`motion:`), the index into q of each entry of
   * driven_coordinates, which index v (the rows of M). NULL means the same
   * indices (planar models, and spatial ones without quaternions). */
  const int* driven_positions;

  /* Closed loops: nc = num_loop_rows constraint rows Phi(q) = 0 in all,
   * num_loops constraints described by `loops` (NULL when none). */
  int num_loop_rows;
  int num_loops;
  const mbfe_loop_constraint_v1* loops;
  /* Phi[nc] (m for positions, a sine or cosine for orientations). */
  void (*loop_constraints)(const double* q, double* Phi);
  /* J[nc * nv] row-major: Phi' = J v (with respect to the velocity
   * coordinates, not the entries of a quaternion). */
  void (*loop_jacobian)(const double* q, double* J);
  /* gamma[nc] = -(dJ/dt) v, so that Phi'' = 0 reads J v' = gamma. */
  void (*loop_gamma)(const double* q, const double* v, double* gamma);

  /* Spatial models: the ground-frame position (m) of a named point, body
   * index and point index, written to xyz[3]. NULL in planar models, which
   * have point_position; a spatial model has this one and point_position
   * NULL. */
  void (*point_position3)(const double* q, int body, int point, double* xyz);
} mbfe_model_v1;

typedef const mbfe_model_v1* (*mbfe_model_entry_fn)(void);

#ifdef __cplusplus
}
#endif

#endif /* MBFE_MODEL_ABI_H_ */
