// What loading a shared library costs a process before `main` (docs/PERFORMANCE.md, "2026-11-24, seventh
// session"): the same empty program, linked against more libraries each time (bench/CMakeLists.txt builds
// library_load_probe_plain, _tbb and _embree), timed by bench/startup.py --probes. The program does nothing, so
// every difference between the three is the dynamic loader's work (mapping, symbol relocation: libembree3 and
// libtbb are linked BIND_NOW) and the libraries' static initialisers.
int main() { return 0; }
