#include "tool/plot_gnuplot.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

extern char** environ;

namespace mbfe::tool {

std::optional<std::string> find_gnuplot() {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) continue;
    const std::string candidate = dir + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

std::string gnuplot_missing_message() {
  return "gnuplot was not found on PATH; install it (Debian: apt-get install gnuplot-nox) to draw PNGs, "
         "or plot the CSV with any other tool";
}

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out + "'";
}

int run_gnuplot(const std::string& gnuplot, const std::string& script) {
  char name[] = "/tmp/mbfe-plot-XXXXXX";
  const int fd = ::mkstemp(name);
  if (fd < 0) return -1;
  ::close(fd);
  {
    std::ofstream out(name);
    out << script;
    if (!out) {
      std::remove(name);
      return -1;
    }
  }
  pid_t pid = 0;
  char* argv[] = {const_cast<char*>(gnuplot.c_str()), name, nullptr};
  if (posix_spawn(&pid, gnuplot.c_str(), nullptr, nullptr, argv, environ) != 0) {
    std::remove(name);
    return -1;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  std::remove(name);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

}  // namespace mbfe::tool
