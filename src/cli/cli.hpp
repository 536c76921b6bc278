#pragma once

namespace hilite::cli {

/// The whole command line: parses, runs a subcommand, prints errors as one line.
/// Exit codes: 0 success, 2 bad input (nothing written), 3 system failure (GL, I/O).
int run(int argc, char** argv);

}  // namespace hilite::cli
