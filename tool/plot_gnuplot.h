// Running gnuplot from the CLI (mbfe plot, mbfe modal --plot): find it, feed it
// a script, report failures as messages, never crash when it is missing.
#pragma once

#include <optional>
#include <string>

namespace mbfe::tool {

/// Absolute path of the gnuplot executable on PATH, or nullopt.
std::optional<std::string> find_gnuplot();

/// "gnuplot not found on PATH; install it (Debian: apt-get install gnuplot-nox) ...".
std::string gnuplot_missing_message();

/// Writes `script` to a temporary file and runs gnuplot on it.
/// @return gnuplot's exit status (0 = success), or -1 if it could not be started.
int run_gnuplot(const std::string& gnuplot, const std::string& script);

/// A gnuplot single-quoted string literal ('it''s').
std::string gnuplot_quote(const std::string& text);

}  // namespace mbfe::tool
