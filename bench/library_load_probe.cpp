// What loading a shared library costs a process before `main` (why Embree is loaded only on first use:
// docs/PERFORMANCE.md, "Embree loaded on first use"): the same empty program, linked against more libraries each time
// (bench/CMakeLists.txt builds library_load_probe_plain, _tbb and _embree), timed by bench/startup.py --probes. The
// program does nothing, so every difference between the three is the dynamic loader's work (mapping, symbol relocation:
// libembree3 and libtbb are linked BIND_NOW) and the libraries' static initialisers.
int main() { return 0; }
