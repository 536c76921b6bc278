// hilite-probe: the child process of a .brdf shader's probe (measurement/shader_probe.hpp), installed in
// <prefix>/libexec so that the library and the Python module probe without the hilite executable.

#include "measurement/shader_probe.hpp"

int main(int argc, char** argv) { return hilite::measurement::probeMain(argc, argv); }
