// LD_PRELOAD shim for the peer races (issue 18): logs, at every glfwSwapBuffers, the wall time and
// the process's CPU time (all threads: llvmpipe rasterises on its own threads) since the previous
// swap, in milliseconds, one "wall cpu" line per frame to $SWAP_LOG (default /tmp/swap.log).
// The same shim goes on every program of a race (a peer and sylva-player in a window under
// xvfb-run), so both are measured at the same point of their frame.
// Build: gcc -O2 -shared -fPIC -o swap-shim.so swap-shim.c -ldl
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

typedef void (*swap_fn)(void*);

static double ms(clockid_t clock) {
  struct timespec t;
  clock_gettime(clock, &t);
  return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

void glfwSwapBuffers(void* window) {
  static swap_fn real = NULL;
  static FILE* log = NULL;
  static double last_wall = -1.0, last_cpu = 0.0;
  if (!real) real = (swap_fn)dlsym(RTLD_NEXT, "glfwSwapBuffers");
  if (!log) {
    const char* path = getenv("SWAP_LOG");
    log = fopen(path ? path : "/tmp/swap.log", "w");
  }
  real(window);
  const double wall = ms(CLOCK_MONOTONIC), cpu = ms(CLOCK_PROCESS_CPUTIME_ID);
  if (log && last_wall >= 0.0) {
    fprintf(log, "%.3f %.3f\n", wall - last_wall, cpu - last_cpu);
    fflush(log);
  }
  last_wall = wall;
  last_cpu = cpu;
}
