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
 */
#ifndef MBFE_MODEL_ABI_H_
#define MBFE_MODEL_ABI_H_

#ifdef __cplusplus
extern "C" {
#endif

#define MBFE_MODEL_ABI_VERSION 3

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
} mbfe_model_v1;

typedef const mbfe_model_v1* (*mbfe_model_entry_fn)(void);

#ifdef __cplusplus
}
#endif

#endif /* MBFE_MODEL_ABI_H_ */
