// `mbfe plot`: the unit of each column (from the sidecar JSON, else from its
// name), panels by unit, and the command through the real binary: against a
// chosen column, two panels, an unknown column refused; bad paths refused
// with exit status 2 (as simulate) before gnuplot starts, the CSV kept.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/support/cli.h"
#include "tests/support/process.h"
#include "tool/plot_columns.h"

namespace mbfe::tool {
namespace {

TEST(PlotColumns, UnitsFromTheNamesWithoutASidecar) {
  const std::map<std::string, std::string> none;
  EXPECT_EQ(column_unit("t", none), "s");
  EXPECT_EQ(column_unit("lambda_tip_slider", none), "N");
  EXPECT_EQ(column_unit("force_tyre", none), "N");
  EXPECT_EQ(column_unit("carriage_drive", none), "N");
  EXPECT_EQ(column_unit("deck@10", none), "m");
  EXPECT_EQ(column_unit("deck@10_dot", none), "m/s");
  EXPECT_EQ(column_unit("beam1_w3", none), "m");
  EXPECT_EQ(column_unit("beam1_dw3", none), "1");
  EXPECT_EQ(column_unit("beam1_dw3_dot", none), "1/s");
  EXPECT_EQ(column_unit("deflection_tyre", none), "m");
  EXPECT_EQ(column_unit("link1", none), "");  // m or rad: only the sidecar knows
  const std::map<std::string, std::string> sidecar = {{"link1", "rad"}, {"link1_dot", "rad/s"}};
  EXPECT_EQ(column_unit("link1", sidecar), "rad");
  EXPECT_EQ(column_unit("link1_dot", sidecar), "rad/s");
  EXPECT_EQ(quantity_of("rad"), "angle");
  EXPECT_EQ(quantity_of("N m"), "torque");
  EXPECT_EQ(quantity_of("furlong"), "value");
}

TEST(PlotColumns, OnePanelPerUnitInOrderOfAppearance) {
  const std::vector<std::string> units = {"s", "m", "N", "m", "rad", "N"};
  const auto panels = panels_by_unit({1, 2, 3, 4, 5}, units);
  ASSERT_EQ(panels.size(), 3u);
  EXPECT_EQ(panels[0], (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(panels[1], (std::vector<std::size_t>{2, 5}));
  EXPECT_EQ(panels[2], (std::vector<std::size_t>{4}));
}

TEST(PlotCommand, AgainstAColumnInPanelsAndUnknownColumnsRefused) {
  test::TempDir dir;
  const std::string csv = (dir / "crossing.csv").string();
  const test::CliRun sim = test::run_cli("simulate models/bridge_moving_mass.yaml --probe deck@10 --t-end 0.3 --quiet --out " +
                                         test::shell_quote(csv));
  ASSERT_EQ(sim.status, 0) << sim.all();
  EXPECT_EQ(sidecar_units(csv).at("carriage"), "m");
  const std::string png = (dir / "crossing.png").string();
  const test::CliRun plot = test::run_cli("plot " + test::shell_quote(csv) + " -o " + test::shell_quote(png) +
                                          " --x carriage --columns deflection_tyre,force_tyre");
  ASSERT_EQ(plot.status, 0) << plot.all();
  const std::string bytes = test::slurp(png);
  ASSERT_GT(bytes.size(), 1000u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const test::CliRun bad = test::run_cli("plot " + test::shell_quote(csv) + " -o " + test::shell_quote(png) + " --x speed");
  EXPECT_EQ(bad.status, 2) << bad.all();
  EXPECT_NE(bad.err.find("--x: no column 'speed' in "), std::string::npos) << bad.err;
}

TEST(PlotCommand, BadPathsAreBadInputAndTheCsvIsKept) {
  test::TempDir dir;
  const std::string csv = (dir / "run.csv").string();
  const test::CliRun sim =
      test::run_cli("simulate models/double_pendulum.yaml --t-end 0.2 --quiet --out " + test::shell_quote(csv));
  ASSERT_EQ(sim.status, 0) << sim.all();
  const std::string before = test::slurp(csv);
  // -o into a folder that does not exist: exit status 1 from gnuplot before,
  // where simulate --out says 2 with the same words.
  test::CliRun r = test::run_cli("plot " + test::shell_quote(csv) + " -o " +
                                 test::shell_quote((dir / "missing" / "x.png").string()));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("x.png: cannot write the output: No such file or directory"), std::string::npos) << r.err;
  // -o onto a folder.
  r = test::run_cli("plot " + test::shell_quote(csv) + " -o " + test::shell_quote(dir.path().string()));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("it is a folder"), std::string::npos) << r.err;
  // -o onto the CSV it draws, under another name (a hard link): refused, the
  // CSV untouched.
  const std::string alias = (dir / "alias.png").string();
  std::filesystem::create_hard_link(csv, alias);
  r = test::run_cli("plot " + test::shell_quote(csv) + " -o " + test::shell_quote(alias));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("that is the input " + csv), std::string::npos) << r.err;
  EXPECT_TRUE(test::slurp(csv) == before) << "the CSV was overwritten";
  // A .npy is not drawn as if it were text.
  r = test::run_cli("plot " + test::shell_quote((dir / "run.npy").string()) + " -o " +
                    test::shell_quote((dir / "x.png").string()));
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("mbfe plot draws a CSV"), std::string::npos) << r.err;
  // /dev/zero was read until memory ran out.
  r = test::run_cli("plot /dev/zero -o " + test::shell_quote((dir / "x.png").string()), test::bounded_run_prefix());
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.err.find("/dev/zero: cannot read the results file: not a regular file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace mbfe::tool
