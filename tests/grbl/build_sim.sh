#!/usr/bin/env bash
# Builds GRBL's simulator for the GRBL oracle: ../shared/grbl/build.sh on a copy of its sources,
# with one change to the simulator's clock (in the copy; nothing of GRBL is kept here).
#
# grbl_sim runs its clock (timers and the stepper interrupt) in one thread and GRBL's main
# loop in another. On a busy computer the main loop's thread waits for a CPU while the clock
# runs on, and two things then happen that a real controller (whose main loop is never away
# for more than microseconds) never sees:
#  - the main loop was preempted inside a critical section (interrupts disabled, `cli()`):
#    the stepper interrupt does not fire, and the steppers stand still from speed;
#  - the main loop does not cut the planner's blocks into step segments in time: the
#    segment buffer runs dry.
# Measured here under load, the first happens hundreds of times in a 10 s program and adds
# 10 to 20 % to GRBL's time; the second was not seen. The change holds the clock while
# either holds during a cycle: while interrupts are disabled, or while at most one segment
# (the one stepping) is left and the planner has a block not yet cut into segments. The
# clock then waits for the main loop instead of outrunning it; GRBL's planner, stepper and
# their arithmetic are untouched. A hold longer than 2 s of real time is given up (the run
# goes on as the unchanged simulator's would) and told on stderr: `starved N`.
#
#   build_sim.sh SHARED_GRBL_DIR OUT_DIR     -> OUT_DIR/grbl_sim, OUT_DIR/gvalidate
set -euo pipefail
src=$(cd "$1" && pwd)
out=$(mkdir -p "$2" && cd "$2" && pwd)
b=$(mktemp -d)
trap 'rm -rf "$b"' EXIT
cp -r "$src/." "$b/"
chmod -R u+w "$b"
# the stepper's side: would a real controller's main loop be ahead here?
cat >>"$b/grbl/stepper.c" <<'C'

/* millpath's GRBL oracle (tests/grbl/build_sim.sh): the simulator's clock asks this */
uint8_t sim_main_loop_behind(void)
{
  uint8_t queued = (segment_buffer_head + SEGMENT_BUFFER_SIZE - segment_buffer_tail) % SEGMENT_BUFFER_SIZE;
  if (!(sys.state & STATE_CYCLE) || (sys.step_control & STEP_CONTROL_END_MOTION)) { return 0; }
  return !(SREG & SEI) || (queued < 2 && plan_get_current_block() != NULL);
}
C
# the clock's side: before each tick, wait (yield) while the main loop is behind
sim=$b/grbl-sim/simulator.c
sed -i 's/\r$//' "$sim" # its lines end in CR LF
grep -q '^   while (sim.masterclock < simulated_ticks){$' "$sim"
grep -q '^  uint64_t simulated_ticks=0;$' "$sim"
sed -i 's|^   while (sim.masterclock < simulated_ticks){$|&\
    if (sim_main_loop_behind()) {\
      uint32_t now = platform_ns();\
      if (!holding) { holding = 1; held_since = now; }\
      if (now - held_since < 2000000000u) { simulated_ticks = sim.masterclock; break; }\
      if (holding == 1) { holding = 2; fprintf(stderr, "starved %u\\n", ++starved); }\
    } else { holding = 0; }|' "$sim"
# its state, kept across the loop's rounds
sed -i 's|^  uint64_t simulated_ticks=0;$|&\
  uint8_t sim_main_loop_behind(void);\
  uint32_t held_since = 0; int holding = 0; unsigned starved = 0;|' "$sim"
bash "$b/build.sh" "$out"
