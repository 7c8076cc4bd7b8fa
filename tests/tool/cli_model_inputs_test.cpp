// The files a model reads besides itself (a beam's profile table) are inputs
// of the run as the model file is, through the real `mbfe` binary: no output
// of simulate, modal, generate or sweep lands on one (exit status 2, the table
// kept, nothing compiled), and a table is read within a stated size.
#include <gtest/gtest.h>

#include <unistd.h>

#include <string>

#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// A profile table covering the 20 m deck, flat.
constexpr const char* kTable = "s,offset\n0,0\n20,0\n";

class ModelInputs : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(tmp_ / "anim" / "frames"); }
  /// The shipped moving-mass bridge with its deck riding on the table
  /// `table` (a path relative to the model), written as tmp/bridge.yaml.
  fs::path model_reading(const std::string& table) {
    std::string text = slurp(fs::path(MBFE_SOURCE_DIR) / "models" / "bridge_moving_mass.yaml");
    const std::string anchor = "    elements: 40\n";
    const std::size_t at = text.find(anchor);
    EXPECT_NE(at, std::string::npos);
    text.insert(at + anchor.size(), "    profile: {file: " + table + "}\n");
    const fs::path model = tmp_ / "bridge.yaml";
    spit(model, text);
    spit(tmp_ / table, kTable);
    return model;
  }
  RunResult mbfe(const std::string& args) {
    return run_mbfe(tmp_, args, "MBFE_CACHE_DIR=" + quote((tmp_ / "cache").string()));
  }
  /// `r` refused an output onto `table`, before any compile, and left it as it was.
  void expect_refused(const RunResult& r, const std::string& output, const fs::path& table) {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(output), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(table.string()), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("compiled"), std::string::npos) << "refused only after a compile: " << r.err;
    EXPECT_EQ(slurp(table), kTable);
  }
  TempDir tmp_;
};

TEST_F(ModelInputs, NoOutputOfSimulateLandsOnAProfileTable) {
  // `simulate m.yaml --out rail.csv` with the deck on profile rail.csv exited
  // 0 and left the run's CSV where the table was.
  const fs::path model = model_reading("rail.csv");
  const fs::path table = tmp_ / "rail.csv";
  fs::create_hard_link(table, tmp_ / "hard.csv");
  fs::create_symlink(table, tmp_ / "soft.csv");
  for (const fs::path& out : {table, tmp_ / "hard.csv", tmp_ / "soft.csv"}) {
    const RunResult r = mbfe("simulate " + quote(model.string()) + " --t-end 0.01 --out " + quote(out.string()));
    expect_refused(r, "--out " + out.string() + ": that is the input " + table.string(), table);
  }
  // The sidecar FILE.json onto the table.
  const fs::path sidecar = tmp_ / "run.csv.json";
  fs::rename(table, sidecar);
  const fs::path model2 = model_reading("run.csv.json");
  ASSERT_EQ(model2, model);
  const RunResult r =
      mbfe("simulate " + quote(model.string()) + " --t-end 0.01 --out " + quote((tmp_ / "run.csv").string()));
  expect_refused(r, "--out (its sidecar) " + sidecar.string(), sidecar);
  EXPECT_FALSE(fs::exists(tmp_ / "run.csv"));
}

TEST_F(ModelInputs, NoAnimationFrameLandsOnAProfileTable) {
  // A table inside the --vtk folder's frames/, which mbfe fills with frames.
  const fs::path model = model_reading("anim/frames/frame_000000.vtp");
  const fs::path table = tmp_ / "anim" / "frames" / "frame_000000.vtp";
  const RunResult r = mbfe("simulate " + quote(model.string()) + " --t-end 0.01 --vtk " +
                           quote((tmp_ / "anim").string()));
  expect_refused(r, "--vtk " + (tmp_ / "anim" / "frames").string() + ": that folder holds the input", table);
}

TEST_F(ModelInputs, NoPictureNorSourceLandsOnAProfileTable) {
  const fs::path model = model_reading("spectrum.png");
  const fs::path picture = tmp_ / "spectrum.png";
  RunResult r = mbfe("modal " + quote(model.string()) + " --plot " + quote(picture.string()));
  expect_refused(r, "--plot " + picture.string() + ": that is the input " + picture.string(), picture);
  fs::create_directories(tmp_ / "gen");
  model_reading("gen/bridge_moving_mass.cpp");
  const fs::path source = tmp_ / "gen" / "bridge_moving_mass.cpp";
  r = mbfe("generate " + quote(model.string()) + " -o " + quote((tmp_ / "gen").string()));
  expect_refused(r, "-o " + source.string() + ": that is the input " + source.string(), source);
}

TEST_F(ModelInputs, NoSweepOutputLandsOnAProfileTable) {
  const fs::path sweep = tmp_ / "sweep.yaml";
  spit(sweep, "sweep: s\nmodel: bridge.yaml\nvary:\n  - {path: contacts.tyre.damping, values: [1000.0]}\n"
              "simulate: {t_end: 0.01}\n");
  const fs::path out = tmp_ / "out";
  fs::create_directories(out / "points" / "0");
  // The summary onto the table, and a table among the points' files.
  for (const std::string& table : {std::string("out/summary.csv"), std::string("out/points/0/run.csv")}) {
    model_reading(table);
    const RunResult r = mbfe("sweep " + quote(sweep.string()) + " --out " + quote(out.string()));
    expect_refused(r, "--out " + out.string(), tmp_ / table);
  }
}

TEST_F(ModelInputs, NoSweepOutputLandsOnATableOnlyALaterPointReads) {
  // The points vary the deck's profile table: the first reads rail.csv, the
  // second the folder's summary.csv, which the sweep would overwrite.
  model_reading("rail.csv");
  const fs::path out = tmp_ / "out";
  fs::create_directories(out);
  spit(out / "summary.csv", kTable);
  const fs::path sweep = tmp_ / "sweep.yaml";
  spit(sweep, "sweep: s\nmodel: bridge.yaml\nvary:\n  - {path: beams.deck.profile.file, values: [rail.csv, "
              "out/summary.csv]}\nsimulate: {t_end: 0.01}\n");
  const RunResult r = mbfe("sweep " + quote(sweep.string()) + " --out " + quote(out.string()));
  expect_refused(r, "--out " + (out / "summary.csv").string() + ": that is the input", out / "summary.csv");
}

TEST_F(ModelInputs, AProfileTableIsReadWithinItsLimit) {
  // A sparse file of 1 GiB (no disk space) was read for more than 50 s up to
  // 2.5 GB of memory; under a memory limit one of 3 GiB said "the file is
  // empty". Refused by its size before a byte is read, at the file: key.
  const fs::path model = model_reading("rail.csv");
  const fs::path table = tmp_ / "rail.csv";
  ASSERT_EQ(::truncate(table.c_str(), off_t{1} << 30), 0);
  RunResult r = mbfe("simulate " + quote(model.string()) + " --t-end 0.01 --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  // Line 32, `    profile: {file: rail.csv}`: the value at column 21.
  EXPECT_NE(r.err.find(model.string() + ":32:21: beam 'deck': profile.file: \"rail.csv\" (" + table.string() +
                       "): the file is 1073741824 bytes, more than the limit of 67108864"),
            std::string::npos)
      << r.err;
  // Bytes that are not text: refused at the file: key, naming where in the table.
  spit(table, std::string("s,offset\n0,0\n\0\0\0\x01", 17));
  r = mbfe("simulate " + quote(model.string()) + " --t-end 0.01 --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(model.string() + ":32:21: beam 'deck': profile.file: \"rail.csv\" is not a CSV table: not a "
                                        "text file: NUL byte at " + table.string() + ":3:1"),
            std::string::npos)
      << r.err;
  // A device or a folder in its place.
  fs::remove(table);
  fs::create_symlink("/dev/zero", table);
  r = mbfe("simulate " + quote(model.string()) + " --t-end 0.01 --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(model.string() + ":32:21: beam 'deck': profile.file: cannot read \"rail.csv\""),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace mbfe::test
