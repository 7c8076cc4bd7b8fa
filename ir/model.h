// The model IR: what a model description file says, validated and resolved.
//
// The YAML front end (frontend/parse_model.h) fills it; the symbolic generator and the runtime read
// it. Nothing here knows YAML or GiNaC. Every name stored here has passed the
// identifier check ([A-Za-z_][A-Za-z0-9_]*), every number is finite, and every
// cross reference (parent, body of a load, beam of a contact) is resolved to an
// index. SI units throughout, ground frame: planar (x, y) unless
// Model::dimension is 3, when the members marked "spatial" hold the model and
// their planar counterparts stay zero (docs/model-format.md, "Spatial models").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ir/expression.h"
#include "ir/source_loc.h"

namespace mbfe::ir {

using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;

/// An inertia tensor about the centre of mass in the body frame, as the six
/// distinct entries of the symmetric matrix [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz],
/// [Ixz, Iyz, Izz]] in this order: Ixx, Iyy, Izz, Ixy, Ixz, Iyz (kg m^2;
/// URDF's ixx, iyy, izz, ixy, ixz, iyz). Validated physical: positive
/// semidefinite, principal moments satisfying the triangle inequality.
using InertiaTensor = std::array<double, 6>;

/// Spherical and free joints exist in spatial models only.
enum class JointType { kRevolute, kPrismatic, kSpherical, kFree };

/// Position coordinates of a joint: 1, a spherical joint's unit quaternion 4,
/// a free joint's position and quaternion 7.
int position_count(JointType type);
/// Velocity coordinates of a joint: 1, 3 (spherical), 6 (free).
int velocity_count(JointType type);

/// The joint connecting a body to its parent.
///
/// Planar models (dimension 2), one coordinate q:
/// Revolute: body frame = parent frame translated to `at`, rotated CCW by q.
/// Prismatic: body frame = parent frame translated to `at + q * axis`, not
/// rotated (`axis` is stored normalised, in the parent frame).
///
/// Spatial models (dimension 3, docs/model-format.md "Spatial models"): the
/// joint frame is the parent frame translated to `at3` and turned by the
/// fixed `rotation` (roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)).
/// Revolute: body frame = joint frame rotated by q about `axis3` (unit, in
/// the joint frame, right-hand rule). Prismatic: body frame = parent frame
/// translated to `at3 + q * axis3` (unit, in the parent frame) and turned by
/// `rotation`. Spherical: joint frame turned by a unit quaternion (4
/// coordinates, 3 velocities: the angular velocity relative to the joint
/// frame, in the body frame). Free: joint frame translated by (x, y, z) in
/// the joint frame, then turned by a unit quaternion (7 coordinates; 6
/// velocities: the rates of x, y, z, then the relative angular velocity in
/// the body frame).
///
/// A driven joint (revolute or prismatic) has a `motion`: q = motion(t), no
/// longer an unknown.
struct Joint {
  JointType type = JointType::kRevolute;
  Vec2 at{0.0, 0.0};    // m, parent frame
  Vec2 axis{1.0, 0.0};  // unit vector, parent frame (prismatic only)
  Vec3 at3{0.0, 0.0, 0.0};        // spatial: m, parent frame
  Vec3 axis3{0.0, 0.0, 1.0};      // spatial: unit vector (revolute: joint frame; prismatic: parent frame)
  Vec3 rotation{0.0, 0.0, 0.0};   // spatial: rad, roll, pitch, yaw of the joint frame
  std::optional<Expression> motion;  // m or rad as a function of t
  SourceLoc loc;
  SourceLoc motion_loc;
};

struct NamedPoint {
  std::string name;
  Vec2 position{0.0, 0.0};  // m, body frame
  Vec3 position3{0.0, 0.0, 0.0};  // spatial: m, body frame
  SourceLoc loc;
};

/// A rigid body; owns the generalized coordinates of its joint (file order:
/// a planar model has one per body, see ir/coordinate_layout.h).
struct Body {
  std::string name;
  int parent = -1;     // index into Model::bodies; -1 = ground
  Joint joint;
  double mass = 0.0;     // kg, >= 0 (0 = fictitious, massless body)
  double inertia = 0.0;  // kg m^2 about the centre of mass, >= 0
  Vec2 com{0.0, 0.0};    // m, body frame
  InertiaTensor inertia3{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // spatial: about the centre of mass, body frame
  Vec3 com3{0.0, 0.0, 0.0};                              // spatial: m, body frame
  std::vector<NamedPoint> points;
  SourceLoc loc;
};

enum class LoadType { kForce, kTorque, kSpringDamper };

/// A load on the rigid part, zero outside `window`. Force: ground-frame force
/// at a named point (or at the body-frame origin when no point is given).
/// Torque: on the body (spatial: a ground-frame vector). Both are expressions
/// in t. SpringDamper: Q_i += -stiffness (q_i - rest) - damping qd_i on the
/// body's own joint coordinate (a revolute or prismatic joint).
struct Load {
  LoadType type = LoadType::kForce;
  int body = -1;        // index into Model::bodies
  int point = -1;       // index into Body::points; -1 = body-frame origin
  std::array<Expression, 2> force;  // N, ground frame
  Expression torque;    // N m
  std::array<Expression, 3> force3;   // spatial: N, ground frame
  std::array<Expression, 3> torque3;  // spatial: N m, ground frame
  TimeWindow window;
  double stiffness = 0.0;  // N/m or N m/rad
  double damping = 0.0;    // N s/m or N m s/rad
  double rest = 0.0;       // m or rad
  SourceLoc loc;
  std::string name;  // optional (empty): how --set and sweeps address it
};

enum class SupportType { kPinned, kClamped, kSpring };

/// pinned fixes w at the node, clamped w and w'; spring holds w elastically:
/// a spring (and damper) to the ground on w, with a lumped mass at the node
/// (the steady arm of a catenary's support).
struct Support {
  double at = 0.0;  // m along the beam
  SupportType type = SupportType::kPinned;
  int node = -1;    // resolved node index (0 .. elements)
  double stiffness = 0.0;  // N/m (spring)
  double damping = 0.0;    // N s/m (spring)
  double mass = 0.0;       // kg (spring)
  SourceLoc loc;
};

/// Transverse point force on a beam at a node; an expression in t, zero
/// outside `window`.
struct BeamPointLoad {
  double at = 0.0;     // m along the beam
  Expression value;    // N, positive to the left of the beam axis
  int node = -1;       // resolved node index
  TimeWindow window;
  SourceLoc loc;
  std::string name;  // optional (empty): how --set and sweeps address it
};

/// A transverse force travelling along a beam: `value` (an expression in t)
/// at s = start + speed (t - t0), through the element's shape functions
/// (consistent nodal loads), while s is in [0, L].
struct BeamMovingLoad {
  Expression value;    // N, positive to the left of the beam axis
  double speed = 0.0;  // m/s, != 0
  double start = 0.0;  // m, position at t = t0
  double t0 = 0.0;     // s
  SourceLoc loc;
  std::string name;  // optional (empty): how --set and sweeps address it
};

/// A point mass at a node (a clamp, a dropper's half): adds to M on w.
struct BeamPointMass {
  double at = 0.0;  // m along the beam
  double mass = 0.0;  // kg, > 0
  int node = -1;      // resolved node index
  SourceLoc loc;
};

/// kMass: the modes kCap changes keep their stiffness and get the modal mass
/// (and damping) that puts their roots where kCap puts them, which keeps the
/// static compliance exact (docs/damping-adjustment.md).
/// kTruncate: modal truncation; the modes with omega_j > omega_limit are
/// removed and the beam moves in its modes below omega_limit alone
/// (docs/damping-adjustment.md, "Policy truncate").
enum class AdjustmentPolicy { kNone, kCap, kPaperEq25, kKeepSlow, kMass, kTruncate };

/// What the modes of an adjustment are the modes of: the beam alone, or the
/// structure of the beams joined to it by links, taut links included
/// (docs/catenary.md, "The joined structure").
enum class AdjustmentScope { kBeam, kJoined };

/// Modal adjustment of damping (Section 6 of the paper; docs/damping-adjustment.md).
struct Adjustment {
  bool present = false;          // the beam has an `adjustment:` block
  double omega_limit = 0.0;      // rad/s (with omega_limit_auto: chosen when the model is assembled)
  /// `omega_limit: auto`: the lowest limit whose accuracy estimate stays
  /// below `tolerance` (docs/damping-adjustment.md, "Choosing omega_limit for a tolerance").
  bool omega_limit_auto = false;
  double tolerance = 0.01;       // the largest estimate allowed with omega_limit_auto (relative)
  SourceLoc omega_limit_loc;     // the omega_limit value, for messages
  double margin = 0.1;           // the paper's l
  double zeta_min = 0.0;         // damping-ratio floor for oscillatory modes
  /// The default, as a block without `policy:` reads (docs/damping-adjustment.md,
  /// "Which policy is the default"); a joined scope takes only kCap.
  AdjustmentPolicy policy = AdjustmentPolicy::kMass;
  AdjustmentScope scope = AdjustmentScope::kBeam;
  SourceLoc loc;
  /// The block is present and changes something (its policy is not `none`).
  bool active() const { return present && policy != AdjustmentPolicy::kNone; }
};

enum class MassLumping { kConsistent, kLumped };

/// The running surface of a beam (`profile:` and `camber:`, docs/profiles.md):
/// what slider contacts ride on is w(s) + r(s) - w_dead(s), r the profile's
/// offset from the beam axis along +w and w_dead the beam's static deflection
/// under its own weight when `camber: static`.
enum class ProfileKind { kNone, kExpression, kTable, kSpectrum };

/// A published track-irregularity spectrum (runtime/fem/track_spectrum.h).
enum class TrackSpectrum { kFra, kGerman };

struct BeamProfile {
  ProfileKind kind = ProfileKind::kNone;
  Expression expression;            // kExpression: r(s) in m, s in m
  std::vector<double> table_s;      // kTable: m, strictly increasing, covers [0, L]
  std::vector<double> table_offset; // kTable: m, one per table_s (linear between)
  std::string table_file;           // kTable: as written, for messages
  std::string table_path;           // kTable: the path opened (table_file against the model file's folder)
  TrackSpectrum spectrum = TrackSpectrum::kFra;  // kSpectrum
  int spectrum_class = 0;           // FRA: 1..6; German: 0 low, 1 high disturbance
  double wavelength_min = 0.0;      // m, > 0 (kSpectrum)
  double wavelength_max = 0.0;      // m, > wavelength_min (kSpectrum)
  std::uint64_t seed = 0;           // kSpectrum
  bool camber_static = false;       // `camber: static`
  SourceLoc loc;
  bool active() const { return kind != ProfileKind::kNone || camber_static; }
};

/// A planar Euler-Bernoulli beam fixed to the ground.
struct Beam {
  std::string name;
  Vec2 origin{0.0, 0.0};  // m, the end s = 0 in the ground frame
  double angle = 0.0;     // rad, axis direction from the ground x axis
  double length = 0.0;    // m, > 0
  int elements = 0;       // > 0
  double area = 0.0;      // m^2 (from `section`)
  double second_moment = 0.0;  // m^4 (from `section`)
  double youngs_modulus = 0.0; // Pa
  double density = 0.0;        // kg/m^3
  double tension = 0.0;   // N, axial pre-tension (>= 0): the geometric stiffness T int(N'^T N') ds
  std::vector<Support> supports;
  std::vector<BeamPointMass> masses;
  double rayleigh_alpha = 0.0;  // 1/s
  double rayleigh_beta = 0.0;   // s
  std::vector<BeamPointLoad> loads;
  std::vector<BeamMovingLoad> moving_loads;
  Adjustment adjustment;
  MassLumping mass = MassLumping::kConsistent;
  SourceLoc loc;
  BeamProfile profile;  // the running surface slider contacts ride on
};

enum class ContactType { kPin, kSliderPin, kSliderSpring };

/// A body vertex pinned to, or sliding along, a beam's neutral axis: pin and
/// slider_pin are constraints (docs/contacts.md); slider_spring is a penalty
/// force N = k delta + c delta' with delta = w(s) - y_P, no constraint.
/// The force law of a slider_spring: linear N = k delta + c delta', or
/// Hertz's N = C_H delta^1.5 + c delta' (a wheel on a rail; zero unless the
/// point penetrates).
enum class ContactLaw { kLinear, kHertz };

struct Contact {
  std::string name;
  ContactType type = ContactType::kPin;
  int body = -1;   // index into Model::bodies
  int point = -1;  // index into Body::points
  int beam = -1;   // index into Model::beams
  double at = 0.0; // m along the beam (pin only)
  double stiffness = 0.0;  // N/m (slider_spring, law linear; 0 for hertz)
  double damping = 0.0;    // N s/m (slider_spring)
  bool unilateral = false; // slider_spring: compression only (lift-off)
  bool from_below = false; // slider_spring: the point presses from the +w side (a pantograph under a wire)
  SourceLoc loc;
  ContactLaw law = ContactLaw::kLinear;  // slider_spring: how N follows delta
  double coefficient = 0.0;  // N/m^1.5 (slider_spring, law hertz: N = coefficient delta^1.5)
  bool is_constraint() const { return type != ContactType::kSliderSpring; }
};

/// A point on a beam, for a link's ends.
struct BeamPointRef {
  int beam = -1;    // index into Model::beams
  double at = 0.0;  // m along the beam (any s in [0, L]: the shape functions interpolate)
};

/// An axial spring (and damper) between two points of two parallel beams, on
/// their transverse displacements: a catenary's dropper. Its tension is
///   T = stiffness (w_b - w_a - rest) + damping (w_b - w_a)',
/// pulling a towards b and b towards a; `slack`: it carries tension only
/// (T = 0 when that is negative). `hold`, when given, fixes `rest` instead:
/// the rest offset that puts point a at w = hold in the static equilibrium of
/// the beams and their links (form finding, docs/catenary.md).
struct Link {
  std::string name;
  BeamPointRef a, b;
  double stiffness = 0.0;  // N/m, > 0
  double damping = 0.0;    // N s/m, >= 0
  bool slack = false;
  double rest = 0.0;       // m
  std::optional<double> hold;  // m
  SourceLoc loc;
};

/// A closed kinematic loop: a constraint between two bodies of the tree
/// (docs/model-format.md, "Closed loops"). With R_a, R_b the body frames
/// and p_a, p_b the two points in the ground frame:
///   point:     p_a = p_b (3 rows in space, 2 in the plane);
///   revolute:  p_a = p_b and b turns relative to a about `axis` only: the
///              axis, fixed in a, keeps the same components in b's frame
///              (space: 5 rows; plane: 2, the axis is z);
///   prismatic: b keeps a's orientation and p_b stays on the line through
///              p_a along `axis` fixed in a (space: 5 rows; plane: 2).
enum class LoopType { kPoint, kRevolute, kPrismatic };

/// One end of a loop: a point of a body, or of the ground.
struct LoopEnd {
  int body = -1;   // index into Model::bodies; -1 = the ground
  int point = -1;  // index into Body::points; -1 when given by coordinates
  Vec3 at{0.0, 0.0, 0.0};  // m, the point in the body frame (the ground's for the ground); z = 0 in the plane
};

struct LoopConstraint {
  std::string name;
  LoopType type = LoopType::kPoint;
  LoopEnd a, b;
  Vec3 axis{0.0, 0.0, 1.0};  // unit vector in a's frame (revolute in space, prismatic); z = 0 in the plane
  SourceLoc loc;
};

/// Constraint rows of a loop of `type` in a model of `dimension` (2 or 3).
int loop_rows(LoopType type, int dimension);

struct Initial {
  std::vector<double> q;   // one per position coordinate, model order (planar: one per body; missing = 0,
                           // a quaternion's missing = identity)
  std::vector<double> qd;  // one per velocity coordinate (planar: one per body)
  bool static_start = false;  // `static: true`: static equilibrium at t = 0
  SourceLoc loc;
  /// Quaternions of `q` that the file gave off unit length (q holds them
  /// scaled to unit): the body, the norm given and where, for the notice a
  /// run prints (and `--strict` refuses).
  struct ScaledQuaternion {
    std::string body;
    double norm = 1.0;
    SourceLoc loc;
  };
  std::vector<ScaledQuaternion> scaled_quaternions;
};

struct Simulation {
  std::string integrator = "rk4";
  double step = 1.0e-3;  // s
  double t_end = 1.0;    // s
  SourceLoc loc;
};

struct Model {
  std::string name;          // identifier
  std::string source_path;   // as given on the command line
  std::string source_sha256; // hex digest of the file's bytes
  int dimension = 2;         // 2: planar; 3: spatial (no beams, contacts or links)
  Vec2 gravity{0.0, 0.0};    // m/s^2, ground frame
  Vec3 gravity3{0.0, 0.0, 0.0};  // spatial: m/s^2, ground frame
  std::vector<Body> bodies;
  std::vector<Load> loads;
  std::vector<Beam> beams;
  std::vector<Contact> contacts;
  std::vector<Link> links;
  std::vector<LoopConstraint> constraints;  // closed loops
  Initial initial;
  Simulation simulation;
};

/// The files reading `model` read besides its own file: each table profile's
/// (BeamProfile::table_path), once each, in model order. An output of a run
/// must not land on any of them.
std::vector<std::string> data_files(const Model& model);

}  // namespace mbfe::ir
