// Every force element's tangent against central differences of its own
// force: add_tangent(c_q = 1, c_v = 0) must be -df/dq and (0, 1) -df/dv over
// the coordinates the element reads, at states of shipped models where the
// contacts press and the links are taut (a few steps into the run, so rates
// are not zero).
//
// What an element documents as left out is left out here too: a slider
// spring's tangent omits N dg/dq and c (dg/dq) q' (slider_spring_force.h), so
// along the positions it is checked in the beam's rows, along q_c, with the
// bodies' rates set to zero; along the rates, everywhere and as the run has them.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "api/simulator.h"
#include "runtime/coupled/coupled_model.h"
#include "runtime/coupled/slider_spring_force.h"
#include "runtime/simulation/assembled_model.h"

namespace {

using mbfe::runtime::ForceArgs;
using mbfe::runtime::ForceElement;
using mbfe::runtime::ForceSink;
using mbfe::runtime::TangentSink;

// Central differences of forces linear in the coordinates (springs, dampers,
// loads) carry round-off only, eps |f| / h ~ 1e-16 * 1e6 / 1e-7: 1e-6 of the
// column's largest entry leaves two orders of margin.
constexpr double kTangentRelTol = 1e-6;
// The differences' own round-off, eps |f| / h, with room for the few
// operations behind f.
constexpr double kRoundOffFactor = 100 * 2.2e-16;
constexpr double kStepRel = 1e-7;  // of the coordinate's scale
constexpr int kStepsIntoTheRun = 40;

struct Column {
  int index;      // in [q_b; q_c]
  bool velocity;  // d/dv rather than d/dq
};

/// f(q, v) of one element over [q_b; q_c] (nb + nc entries).
Eigen::VectorXd force_of(const ForceElement& e, mbfe::runtime::ForceState& state, double t,
                         const Eigen::VectorXd& q, const Eigen::VectorXd& v, int nb) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(q.size());
  ForceArgs x{t, q.data(), v.data(), q.data() + nb, v.data() + nb};
  ForceSink sink{f.data(), f.data() + nb};
  e.add_force(x, state, sink);
  return f;
}

void check_model(const std::string& file) {
  SCOPED_TRACE(file);
  const mbfe::Model model = mbfe::Model::load(std::string(MBFE_SOURCE_DIR) + "/" + file);
  mbfe::Simulator sim(model, model.request());
  sim.advance_steps(kStepsIntoTheRun);
  Eigen::VectorXd q, v;
  sim.state(q, v);
  const double t = sim.time();
  const auto coupled = model.assembled().coupled_model(true);
  const int nb = coupled->nb(), n = coupled->n();
  ASSERT_EQ(q.size(), n);
  ASSERT_FALSE(coupled->forces().empty());
  int checked = 0;
  for (const auto& element : coupled->forces()) {
    SCOPED_TRACE(element->name());
    const bool slider = dynamic_cast<const mbfe::runtime::SliderSpringForce*>(element.get()) != nullptr;
    auto state = element->make_state();
    const Eigen::VectorXd f0 = force_of(*element, *state, t, q, v, nb);  // and the state add_tangent reads
    // The tangent at this state: position and rate parts apart.
    std::vector<Eigen::Triplet<double>> tq, tv;
    TangentSink sink_q(tq), sink_v(tv);
    ForceArgs x{t, q.data(), v.data(), q.data() + nb, v.data() + nb};
    element->add_tangent(x, *state, 0.0, 1.0, sink_v);
    if (slider) {  // the position tangent where the bodies are at rest
      Eigen::VectorXd rest = v;
      rest.head(nb).setZero();
      force_of(*element, *state, t, q, rest, nb);
    }
    element->add_tangent(x, *state, 1.0, 0.0, sink_q);
    Eigen::SparseMatrix<double> Kt(n, n), Ct(n, n);
    Kt.setFromTriplets(tq.begin(), tq.end());
    Ct.setFromTriplets(tv.begin(), tv.end());

    std::vector<int> read;
    element->beam_dofs_read(q.data(), read);
    std::vector<Column> columns;
    for (int i : read) columns.push_back({nb + i, false}), columns.push_back({nb + i, true});
    for (int i = 0; i < nb; ++i) {
      if (!slider) columns.push_back({i, false});
      columns.push_back({i, true});
    }
    for (const Column& c : columns) {
      // A slider's position columns: the bodies at rest (see the top).
      Eigen::VectorXd v_at = v;
      if (slider && !c.velocity) v_at.head(nb).setZero();
      Eigen::VectorXd qp = q, qm = q, vp = v_at, vm = v_at;
      Eigen::VectorXd& xp = c.velocity ? vp : qp;
      Eigen::VectorXd& xm = c.velocity ? vm : qm;
      const double h = kStepRel * std::max(1.0, std::abs(xp[c.index]));
      xp[c.index] += h;
      xm[c.index] -= h;
      const Eigen::VectorXd fd =
          -(force_of(*element, *state, t, qp, vp, nb) - force_of(*element, *state, t, qm, vm, nb)) / (2.0 * h);
      Eigen::VectorXd tangent = Eigen::VectorXd((c.velocity ? Ct : Kt).col(c.index));
      Eigen::VectorXd differences = fd;
      if (slider && !c.velocity) {  // the rigid rows leave N dg/dq out
        tangent.head(nb).setZero();
        differences.head(nb).setZero();
      }
      const double scale = std::max({differences.cwiseAbs().maxCoeff(), tangent.cwiseAbs().maxCoeff(), 1e-300});
      const double noise = kRoundOffFactor * f0.cwiseAbs().maxCoeff() / h;
      Eigen::Index row = 0;
      const double worst = (differences - tangent).cwiseAbs().maxCoeff(&row);
      EXPECT_LE(worst, kTangentRelTol * scale + noise)
          << (c.velocity ? "d/dv" : "d/dq") << " column " << c.index << ", row " << row << " (nb = " << nb
          << "): differences " << differences[row] << ", tangent " << tangent[row];
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(ForceElementTangents, SliderSpringOfTheMovingMassBridge) { check_model("models/bridge_moving_mass.yaml"); }

TEST(ForceElementTangents, DroppersAndContactOfTheTwoSpanCatenary) {
  check_model("models/pantograph_catenary_2span.yaml");
}

TEST(ForceElementTangents, SpringsOfTheTwoAxleVehicleOnThreeBeams) {
  check_model("models/bridge_two_axle_vehicle.yaml");
}

// A time load depends on t alone: no tangent, and none by differences.
TEST(ForceElementTangents, TimeLoadOfABeam) { check_model("examples/stepping_load/bridge_with_load.yaml"); }

}  // namespace
