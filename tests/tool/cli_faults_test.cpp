// Faults at the command line, through the real `mbfe` binary: numerical
// failures keep the output written so far (flushed, whole lines) and exit with
// status 3; Ctrl-C, SIGTERM and SIGHUP stop cleanly, the sidecar written; bad
// flags, a missing model file, an unwritable --out, an output that would
// overwrite the model, a --vtk folder that is a file and too many frames exit
// with status 2 and say what is wrong; a path that is not UTF-8 still gets its
// sidecar.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include <csignal>
#include <cstring>
#include <regex>
#include <string>

#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// The number N of "...; N rows written..." in a message, or -1.
long rows_in_message(const std::string &err) {
  std::smatch m;
  static const std::regex re("(\\d+) rows written");
  return std::regex_search(err, m, re) ? std::stol(m[1]) : -1;
}

class CliFaults : public ::testing::Test {
protected:
  static fs::path source_model() {
    return fs::path(MBFE_SOURCE_DIR) / "models" / "double_pendulum.yaml";
  }
  std::string env() const {
    return "MBFE_CACHE_DIR=" + quote((tmp_ / "cache").string());
  }
  RunResult mbfe(const std::string &args) {
    return run_mbfe(tmp_, args, env());
  }
  TempDir tmp_;
};

TEST_F(CliFaults, MasslessChainEndIsNamedAndThePartialCsvKept) {
  const fs::path model = tmp_ / "massless.yaml";
  spit(model, "model: massless_end\n"
              "gravity: [0, -9.81]\n"
              "bodies:\n"
              "  - {name: link1, parent: ground, joint: {type: revolute, at: "
              "[0, 0]}, mass: 1, inertia: 0.1, com: [0.5, 0]}\n"
              "  - {name: dangling, parent: link1, joint: {type: revolute, at: "
              "[1, 0]}, mass: 0, inertia: 0}\n"
              "simulation: {integrator: rk4, step: 1.0e-3, t_end: 0.1}\n");
  const fs::path csv = tmp_ / "out.csv";
  const RunResult r = mbfe("simulate " + quote(model.string()) + " --out " +
                           quote(csv.string()));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("mass matrix M(q) is singular"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("bodies with mass 0 and inertia 0: dangling"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("link1;"), std::string::npos)
      << "the massive body is not blamed: " << r.err;
  const std::string text = slurp(csv);
  EXPECT_EQ(text.rfind("t,link1,dangling,link1_dot,dangling_dot\n", 0), 0u)
      << text;
  const std::size_t rows = check_complete_csv(text);
  EXPECT_EQ(static_cast<long>(rows), rows_in_message(r.err)) << r.err;
}

TEST_F(CliFaults, DivergingRigidSimulationExits3WithTheRowsSoFarFlushed) {
  // A 1 kg slider on a 1e6 N/m spring: omega = 1000 rad/s; forward Euler with
  // h = 1e-2 multiplies the amplitude by sqrt(1 + (h omega)^2) ~ 10 a step.
  const fs::path model = tmp_ / "stiff.yaml";
  spit(model,
       "model: stiff_spring\n"
       "gravity: [0, 0]\n"
       "bodies:\n"
       "  - {name: slider, parent: ground, joint: {type: prismatic, axis: [1, "
       "0], at: [0, 0]}, mass: 1, inertia: 0}\n"
       "loads:\n"
       "  - {type: spring_damper, joint: slider, stiffness: 1.0e6, damping: 0, "
       "rest: 0}\n"
       "initial: {q: {slider: 0.01}}\n"
       "simulation: {integrator: forward_euler, step: 1.0e-2, t_end: 100}\n");
  const fs::path csv = tmp_ / "out.csv";
  const RunResult r = mbfe("simulate " + quote(model.string()) +
                           " --every 1 --out " + quote(csv.string()));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("diverged at t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("forward_euler"), std::string::npos) << r.err;
  const std::string text = slurp(csv);
  const std::size_t rows = check_complete_csv(text);
  EXPECT_GE(rows, 5u);
  EXPECT_LT(rows, 1000u); // stopped long before t_end = 100 s (10,000 steps)
  EXPECT_EQ(static_cast<long>(rows), rows_in_message(r.err)) << r.err;
  // Every row written is finite: the diverged state itself is not written.
  const auto lines = lines_of(text);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].find("inf"), std::string::npos) << lines[i];
    EXPECT_EQ(lines[i].find("nan"), std::string::npos) << lines[i];
  }
}

// Ctrl-C, a batch system's SIGTERM and a closed terminal's SIGHUP all stop a
// run the same way: the rows so far kept and flushed, exit 3.
TEST_F(CliFaults,
       SigintSigtermAndSighupStopARunningSimulationWithThePartialCsvIntact) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    SCOPED_TRACE(strsignal(signal));
    const fs::path csv = tmp_ / ("long" + std::to_string(signal) + ".csv");
    // About 1e9 steps: hours. Rows every 1000 steps, flushed every 256 rows.
    Spawned run({MBFE_CLI, "simulate",
                 std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum.yaml",
                 "--step", "1e-6", "--t-end", "1000", "--every", "1000",
                 "--out", csv.string()},
                {"MBFE_CACHE_DIR=" + (tmp_ / "cache").string()},
                tmp_ / "sigint.stdout", tmp_ / "sigint.stderr");
    ASSERT_GT(run.pid(), 0);
    // Wait until it is integrating (the solver compiles first): the CSV has
    // rows.
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::seconds(300);
    while (run.running() && std::chrono::steady_clock::now() < deadline) {
      std::error_code ec;
      if (fs::file_size(csv, ec) > 4096 && !ec)
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_TRUE(run.running())
        << "mbfe ended before the signal: " << slurp(tmp_ / "sigint.stderr");
    ASSERT_EQ(::kill(run.pid(), signal), 0);
    const int status = run.wait_for(60);
    ASSERT_NE(status, -1) << "mbfe did not stop within 60 s of the signal";
    const std::string err = slurp(tmp_ / "sigint.stderr");
    EXPECT_EQ(status, 3) << err;
    EXPECT_NE(err.find("interrupted at t = "), std::string::npos) << err;
    const std::string text = slurp(csv);
    EXPECT_EQ(text.rfind("t,link1,link2,link1_dot,link2_dot\n", 0), 0u);
    const std::size_t rows = check_complete_csv(text);
    EXPECT_GE(rows, 10u);
    EXPECT_EQ(static_cast<long>(rows), rows_in_message(err)) << err;
    // The record beside the CSV is written too, says how the run ended and
    // counts the rows the CSV holds.
    const nlohmann::json record = nlohmann::json::parse(slurp(csv.string() + ".json"), nullptr, false);
    ASSERT_TRUE(record.is_object()) << slurp(csv.string() + ".json");
    EXPECT_EQ(record.value("status", ""), "interrupted");
    EXPECT_EQ(record.value("rows", -1L), static_cast<long>(rows));
  }
}

TEST_F(CliFaults, BadFlagsExit2) {
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"simulate models/double_pendulum.yaml --frobnicate",
       "unknown flag --frobnicate"},
      {"simulate models/double_pendulum.yaml --step", "--step"},
      {"simulate models/double_pendulum.yaml --step -1", "--step must be > 0"},
      {"simulate models/double_pendulum.yaml --step abc", "--step"},
      {"simulate models/double_pendulum.yaml --step nan", "--step"},
      {"simulate models/double_pendulum.yaml --t-end 0", "--t-end must be > 0"},
      {"simulate models/double_pendulum.yaml --every 0", "--every"},
      {"simulate models/double_pendulum.yaml --integrator nonsense",
       "nonsense"},
      {"simulate models/bridge_moving_mass.yaml --probe deck@10,deck@5,deck@10",
       "--probe: 'deck@10' is given twice"},
      {"simulate", "expected one model file"},
      {"simulate a.yaml b.yaml", "expected one model file"},
      {"eval models/double_pendulum.yaml --q 1,2,3", "--q"},
      {"frobnicate models/double_pendulum.yaml",
       "unknown command 'frobnicate'"},
  };
  for (const Case &c : cases) {
    const RunResult r = mbfe(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n"
                                                        << r.err;
    EXPECT_EQ(r.err.find("error: "), std::string::npos)
        << "an internal error, not a usage error: " << r.err;
  }
}

TEST_F(CliFaults, MissingModelFileExits2NamingTheFile) {
  const std::string missing = (tmp_ / "no_such_model.yaml").string();
  for (const char *command : {"simulate", "eval", "generate", "modal"}) {
    const std::string extra = std::string(command) == "generate"
                                  ? " -o " + quote((tmp_ / "gen").string())
                                  : "";
    const RunResult r =
        mbfe(std::string(command) + " " + quote(missing) + extra);
    EXPECT_EQ(r.status, 2) << command << ": " << r.err;
    EXPECT_EQ(r.err.rfind(missing + ":", 0), 0u) << command << ": " << r.err;
  }
}

TEST_F(CliFaults, OutIntoAMissingFolderExits2AndWritesNothing) {
  const fs::path out = tmp_ / "no_such_folder" / "x.csv";
  const RunResult r =
      mbfe("simulate models/double_pendulum.yaml --t-end 0.01 --out " +
           quote(out.string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(out.string() +
                       ": cannot write the output: No such file or directory"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out.parent_path()));
}

TEST_F(CliFaults, AnOutputNamingTheModelIsRefusedAndTheModelKept) {
  // --out naming the model file overwrote it with the CSV.
  const fs::path model = tmp_ / "run.yaml";
  fs::copy_file(source_model(), model);
  const std::string text = slurp(model);
  // The model itself, a hard link to it, a symbolic link to it, and a CSV
  // whose sidecar (FILE.json) would be the model.
  fs::create_hard_link(model, tmp_ / "hard.csv");
  fs::create_symlink(model, tmp_ / "soft.csv");
  const fs::path sidecar_model = tmp_ / "out.csv.json";
  fs::copy_file(source_model(), sidecar_model);
  for (const fs::path &out : {model, tmp_ / "hard.csv", tmp_ / "soft.csv"}) {
    const RunResult r = mbfe("simulate " + quote(model.string()) +
                             " --t-end 0.01 --out " + quote(out.string()));
    EXPECT_EQ(r.status, 2) << out << "\n" << r.err;
    EXPECT_NE(r.err.find("--out " + out.string() + ": that is the input " +
                         model.string()),
              std::string::npos)
        << r.err;
  }
  EXPECT_EQ(slurp(model), text);
  const RunResult r =
      mbfe("simulate " + quote(sidecar_model.string()) +
           " --t-end 0.01 --out " + quote((tmp_ / "out.csv").string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("its sidecar"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(sidecar_model), text);
  EXPECT_FALSE(fs::exists(tmp_ / "out.csv"));
  // generate -o: the sources may not land on the model either.
  const fs::path gen = tmp_ / "gen";
  fs::create_directories(gen);
  fs::copy_file(source_model(), gen / "double_pendulum.cpp");
  const RunResult g =
      mbfe("generate " + quote((gen / "double_pendulum.cpp").string()) +
           " -o " + quote(gen.string()));
  EXPECT_EQ(g.status, 2) << g.err;
  EXPECT_EQ(slurp(gen / "double_pendulum.cpp"), text);
}

TEST_F(CliFaults, OutputFoldersThatAreFilesAreBadInputFoundFirst) {
  // --vtk onto an existing file: exit status 1 and a filesystem error.
  const fs::path file = tmp_ / "not_a_folder";
  spit(file, "x");
  RunResult r =
      mbfe("simulate models/double_pendulum.yaml --t-end 0.01 --quiet --vtk " +
           quote(file.string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(
      r.err.find("--vtk " + file.string() + ": exists and is not a folder"),
      std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("error: "), std::string::npos) << r.err;
  r = mbfe("generate models/double_pendulum.yaml -o " + quote(file.string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("-o " + file.string() + ": exists and is not a folder"),
            std::string::npos)
      << r.err;
  // --out onto a folder, before the solver is compiled.
  r = mbfe("simulate models/double_pendulum.yaml --t-end 0.01 --out " +
           quote(tmp_.path().string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("it is a folder"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("compiled"), std::string::npos) << r.err;
}

TEST_F(CliFaults, AnimationFramesAreCapped) {
  // --vtk-frames 100000000 wrote a frame per row (100,001 files, 403 MB, on a
  // long run); 1e300 was cast to int.
  const fs::path dir = tmp_ / "anim";
  for (const char *frames : {"100000000", "1e300", "10001"}) {
    const RunResult r = mbfe(
        "simulate models/double_pendulum.yaml --t-end 0.01 --quiet --vtk " +
        quote(dir.string()) + " --vtk-frames " + frames);
    EXPECT_EQ(r.status, 2) << frames << "\n" << r.err;
    EXPECT_NE(r.err.find("--vtk-frames: at most 10000 frames"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir));
  const RunResult ok =
      mbfe("simulate models/double_pendulum.yaml --t-end 0.01 --quiet --vtk " +
           quote(dir.string()) + " --vtk-frames 10000");
  EXPECT_EQ(ok.status, 0) << ok.err;
}

TEST_F(CliFaults, AModelPathThatIsNotUtf8StillGetsItsSidecar) {
  // The sidecar names the model file; a byte 0xFF in its name made the JSON
  // writer throw after the run: exit status 1 and an empty sidecar.
  const fs::path model = tmp_ / "model_\xFF.yaml";
  fs::copy_file(source_model(), model);
  const fs::path csv = tmp_ / "out.csv";
  const RunResult r =
      mbfe("simulate " + quote(model.string()) +
           " --t-end 0.01 --quiet --out " + quote(csv.string()));
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string sidecar = slurp(csv.string() + ".json");
  // The byte is written as U+FFFD (EF BF BD), the rest as it was.
  EXPECT_NE(sidecar.find("model_\xEF\xBF\xBD.yaml"), std::string::npos)
      << sidecar;
  EXPECT_NE(sidecar.find("\"status\": \"completed\""), std::string::npos)
      << sidecar;
}

TEST_F(CliFaults,
       StepCountsBeyondTheLimitAreRefusedAndALongStepIsShortenedToTheRun) {
  // 1e19 steps overflowed the count: "0 rk4 steps ... completed", exit 0.
  RunResult r = mbfe("simulate models/double_pendulum.yaml --step 1e-10 "
                     "--t-end 1e9 --quiet --out " +
                     quote((tmp_ / "never.csv").string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("the run needs 1e+19 steps"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("more than the limit of 9007199254740992 (2^53)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(tmp_ / "never.csv"));
  // A step of 1e300 s over a 1 s run took no step and said completed: now
  // one step of 1 s, its row at t = 1.
  const fs::path csv = tmp_ / "one.csv";
  r = mbfe(
      "simulate models/double_pendulum.yaml --step 1e300 --t-end 1 --out " +
      quote(csv.string()));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("1 rk4 steps of 1 s to t = 1 s"), std::string::npos)
      << r.err;
  const Csv rows = read_csv(csv.string());
  ASSERT_EQ(rows.rows.size(), 2u);
  EXPECT_EQ(rows.rows.back()[0], 1.0);
}

TEST_F(CliFaults, BadInputFoundAfterTheOutputOpenedRemovesOnlyARegularFile) {
  // Bad input found once the output is open (here the step count, refused by
  // the driver after the header) removes the empty output: it removed
  // whatever --out named, a device or a pipe too (as root, --out /dev/null
  // took /dev/null off the machine). A pipe with a reader stands in for it.
  const fs::path pipe = tmp_ / "pipe";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const std::string reader =
      "{ cat " + quote(pipe.string()) + " >/dev/null & } && " + env();
  const RunResult r = run_mbfe(tmp_,
                               "simulate models/double_pendulum.yaml --step "
                               "1e-10 --t-end 1e9 --quiet --out " +
                                   quote(pipe.string()),
                               reader);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(fs::is_fifo(pipe)) << "the pipe was removed";
  // A regular file is still removed.
  const fs::path csv = tmp_ / "empty.csv";
  const RunResult f = mbfe("simulate models/double_pendulum.yaml --step 1e-10 "
                           "--t-end 1e9 --quiet --out " +
                           quote(csv.string()));
  EXPECT_EQ(f.status, 2) << f.err;
  EXPECT_FALSE(fs::exists(csv));
}

} // namespace
} // namespace mbfe::test
