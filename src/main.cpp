#include "cli/cli.hpp"

int main(int argc, char** argv) { return hilite::cli::run(argc, argv); }
