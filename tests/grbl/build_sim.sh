#!/usr/bin/env bash
# Builds GRBL's simulator for the GRBL oracle: ../shared/grbl/build.sh on a copy of its sources,
# with changes to the simulator's clock and I/O (in the copy; nothing of GRBL is kept here).
# GRBL's planner, stepper and their arithmetic are untouched.
#
# grbl_sim runs its clock (timers, the stepper interrupt, the serial line) in one thread,
# ticking the AVR's 16 MHz one by one, and GRBL's main loop in another. Unchanged it runs at
# a fifth of real time or slower on a busy computer, and its main loop falls behind the
# clock in ways a real controller's (never away for more than microseconds) never does: the
# stepper interrupt waits while the main loop was preempted inside cli(), the segment buffer
# runs low, the planner holds fewer blocks than it would (10 to 20 % more GRBL time measured
# under load; and up to 2 % from the clock factor `-t` alone). The changes:
#  - quiet ticks counted at once: ticks in which no timer reaches a compare value, overflows
#    or rolls over, no interrupt is pending, no serial byte is due and no report is printed
#    change nothing but the counters (sim_quiet_ticks, sim_count_ticks);
#  - the clock waits for the main loop (sim_main_loop_behind) during a cycle while interrupts
#    are disabled, or while the segment buffer has room and a planner block is left to cut;
#  - the clock waits for the main loop and the sender (sim_waiting_for_sender) while the
#    planner has room and GRBL is not waiting for it to empty (G4, M3/M5, program end, a probe
#    cycle) nor dwelling: while GRBL has received bytes it has not read, and during a cycle
#    until the sender's next bytes come or its input ends;
#  - stdin is read ahead with one read() for many bytes (GRBL still gets one per byte time);
#    its end ends the simulator once GRBL is idle;
#  - dwells (_delay_ms) wait on the simulated clock, not on the wall clock, and the clock
#    stops at a dwell's end until the main loop has seen it;
#  - the probe input is idle (G38.3 runs its move out; G38.2 ends in ALARM:5);
#  - a clock factor of thousands no longer overflows the clock's 32-bit nanoseconds.
# With `-t 1000` a program then takes a third to a half of its GRBL time here, and its time
# is the same at -t 1, 10 and 1000 (within 0.05 %). A wait longer than 2 s (3 s for the
# sender) of real time is given up and told on stderr (`starved N`, `waited N`); the sender
# counts either as a stall and runs the program again.
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
  if (!(sys.state & STATE_CYCLE) || (sys.step_control & STEP_CONTROL_END_MOTION)) { return 0; }
  /* inside cli(), or the segment buffer has room and a planner block is left to cut */
  return !(SREG & SEI) || (segment_next_head != segment_buffer_tail && plan_get_current_block() != NULL);
}
C
# GRBL's main loop, when it waits for the planner to empty (G4, M3, M5, program end)
proto=$b/grbl/protocol.c
grep -q '^void protocol_buffer_synchronize()$' "$proto"
sed -i 's|^void protocol_buffer_synchronize()$|void protocol_buffer_synchronize_grbl()|' "$proto"
cat >>"$proto" <<'C'

/* millpath's GRBL oracle: the simulator's clock asks whether the main loop waits for motion */
volatile uint8_t sim_synchronizing = 0;
void protocol_buffer_synchronize()
{
  sim_synchronizing++; /* a count: the probe cycle synchronizes inside its own wait */
  protocol_buffer_synchronize_grbl();
  sim_synchronizing--;
}
C
sed -i 's|^void protocol_buffer_synchronize_grbl()$|void protocol_buffer_synchronize();\n&|' "$proto"
# and when it waits for a probe move to end (G38.x: no contact here, the move runs out)
mc=$b/grbl/motion_control.c
grep -q '^uint8_t mc_probe_cycle(float \*target, plan_line_data_t \*pl_data, uint8_t parser_flags)$' "$mc"
sed -i 's|^uint8_t mc_probe_cycle(float \*target, plan_line_data_t \*pl_data, uint8_t parser_flags)$|uint8_t mc_probe_cycle_grbl(float *target, plan_line_data_t *pl_data, uint8_t parser_flags)|' "$mc"
cat >>"$mc" <<'C'

/* millpath's GRBL oracle: the probe cycle waits for its move as a buffer synchronize does */
extern volatile uint8_t sim_synchronizing;
uint8_t mc_probe_cycle(float *target, plan_line_data_t *pl_data, uint8_t parser_flags)
{
  uint8_t r;
  sim_synchronizing++;
  r = mc_probe_cycle_grbl(target, pl_data, parser_flags);
  sim_synchronizing--;
  return r;
}
C
sim=$b/grbl-sim/simulator.c
sed -i 's/\r$//' "$sim" "$b/grbl-sim/platform_LINUX.c" "$b/grbl-sim/util/delay.c" # CR LF lines
# the simulator's own stdin reader, dwell and clock rate are replaced (below)
sed -i 's|^uint8_t platform_poll_stdin() {$|uint8_t platform_poll_stdin_unused() {|' "$b/grbl-sim/platform_LINUX.c"
sed -i 's|^void _delay_ms(int i) {$|void _delay_ms_unused(int i) {|; s|^void _delay_us(int i) {$|void _delay_us_unused(int i) {|' \
  "$b/grbl-sim/util/delay.c"
grep -q '^uint8_t platform_poll_stdin_unused() {$' "$b/grbl-sim/platform_LINUX.c"
grep -q '^void _delay_us_unused(int i) {$' "$b/grbl-sim/util/delay.c"
grep -q '^   while (sim.masterclock < simulated_ticks){$' "$sim"
grep -q '^  uint64_t simulated_ticks=0;$' "$sim"
grep -q '^    uint32_t ns_elapsed = (ns_now-ns_prev)\*sim.speedup;' "$sim"
# a clock factor of thousands overflows the 32-bit nanoseconds of one round
sed -i 's|^    uint32_t ns_elapsed = (ns_now-ns_prev)\*sim.speedup;.*$|    uint64_t ns_elapsed = (uint64_t)((double)(uint32_t)(ns_now-ns_prev)*sim.speedup);|' "$sim"
sed -i 's|^   while (sim.masterclock < simulated_ticks){$|&\
    if (sim_main_loop_behind()) {\
      uint32_t now = platform_ns();\
      simulate_write_interrupt();\
      if (!holding) { holding = 1; held_since = now; }\
      if (now - held_since < 2000000000u) { simulated_ticks = sim.masterclock; platform_sleep(20); break; }\
      if (holding == 1) { holding = 2; fprintf(stderr, "starved %u\\n", ++starved); }\
    } else { holding = 0; }\
    if (!no_wait \&\& sim_waiting_for_sender()) {\
      uint32_t now = platform_ns();\
      if (!waiting) { waiting = 1; waiting_since = now; }\
      if (now - waiting_since < 3000000000u) { simulated_ticks = sim.masterclock; platform_sleep(20); break; }\
      if (waiting == 1) { waiting = 2; fprintf(stderr, "waited %u\\n", ++waited); }\
    } else { waiting = 0; }\
    if (!single_ticks \&\& sim.masterclock + 2 < next_byte_tick \&\& sim.masterclock + 2 < simulated_ticks) {\
      uint64_t limit = next_byte_tick - sim.masterclock - 1, quiet;\
      uint64_t print_tick = (uint64_t)(next_print_time * F_CPU);\
      if (simulated_ticks - sim.masterclock - 1 < limit) { limit = simulated_ticks - sim.masterclock - 1; }\
      if (next_print_time > 0 \&\& print_tick < sim.masterclock + 2) { limit = 0; }\
      else if (next_print_time > 0 \&\& print_tick - sim.masterclock - 2 < limit) { limit = print_tick - sim.masterclock - 2; }\
      if (limit > 4096) { limit = 4096; }\
      quiet = sim_quiet_ticks(limit);\
      if (quiet > 1) {\
        sim_count_ticks(quiet);\
        sim.masterclock += quiet;\
        sim.sim_time = (float)sim.masterclock/F_CPU;\
        sim_hook[sh_TICK]();\
        continue;\
      }\
    }|' "$sim"
# its state, kept across the loop's rounds
sed -i 's|^  uint64_t simulated_ticks=0;$|&\
  uint8_t sim_main_loop_behind(void); int sim_waiting_for_sender(void); void simulate_write_interrupt();\
  uint64_t sim_quiet_ticks(uint64_t limit); void sim_count_ticks(uint64_t ticks); extern double next_print_time;\
  uint32_t held_since = 0; int holding = 0; unsigned starved = 0;\
  uint32_t waiting_since = 0; int waiting = 0; unsigned waited = 0;\
  int single_ticks = getenv("GRBL_SIM_SINGLE_TICKS") != NULL, no_wait = getenv("GRBL_SIM_NO_WAIT") != NULL;\
  extern __thread int sim_in_clock_thread; sim_in_clock_thread = 1;\
  void sim_probe_idle(void); sim_probe_idle();|' "$sim"
cat >>"$sim" <<'C'

/* millpath's GRBL oracle (tests/grbl/build_sim.sh) */
#include <errno.h>
#include <sys/prctl.h>
/* The simulator sleeps 0 µs in GRBL's main loop at every serial_read(), in its clock's loop
   at every round, and 20 µs at every wait above: Linux stretches each by the thread's timer
   slack (50 µs), which on an idle computer nothing cuts short. A slack of 1 µs, set before
   the threads start (they inherit it). */
__attribute__((constructor)) static void sim_timer_slack(void) { prctl(PR_SET_TIMERSLACK, 1000UL, 0, 0, 0); }
#include <fcntl.h>
#include <unistd.h>
#include "../system.h"
#include "../planner.h"
__thread int sim_in_clock_thread = 0;

/* the probe input idle (not touching), as a machine with $6=0 and an open probe has it:
   G38.3 then runs its move out, G38.2 ends in ALARM:5 */
void sim_probe_idle(void) { PROBE_PIN |= PROBE_MASK; }
extern volatile uint8_t sim_synchronizing;

/* stdin, read ahead into a buffer (one read for many bytes); GRBL still gets one byte per
   byte time of its serial line. A read that found nothing is tried again only every 32nd
   byte time: while GRBL waits for the sender, the clock is held (below) and reads at once. */
static uint8_t in_buf[4096];
static int in_len = 0, in_pos = 0, in_eof = 0, in_idle = 0;
static int in_fill(void)
{
  static int nonblocking = 0;
  ssize_t n;
  if (in_pos < in_len) { return 1; }
  if (in_eof) { return 0; }
  if (!nonblocking) { fcntl(0, F_SETFL, fcntl(0, F_GETFL) | O_NONBLOCK); nonblocking = 1; }
  n = read(0, in_buf, sizeof in_buf);
  if (n > 0) { in_len = (int)n; in_pos = 0; return 1; }
  if (n == 0 || (errno != EAGAIN && errno != EINTR)) { in_eof = 1; }
  return 0;
}
uint8_t platform_poll_stdin(void)
{
  if (in_pos >= in_len && !in_eof && in_idle++ % 32) { return 0; }
  if (in_fill()) { in_idle = 0; return in_buf[in_pos++]; }
  return in_eof ? 0xFF : 0; /* end of input: the simulator ends once GRBL is idle */
}

/* While GRBL's planner has room and its main loop is not waiting for the planner to empty
   (or in a dwell), a real main loop (ahead of the machine by far) reads every byte received
   before the next arrives, and, while a cycle runs and the sender has not ended its input, a
   real sender keeps the planner filled: the clock waits for them. The answers GRBL
   has written are sent meanwhile, or the sender could not go on. */
void simulate_write_interrupt();
extern volatile uint8_t serial_rx_buffer_head, serial_rx_buffer_tail;
static volatile uint8_t sim_delaying = 0;
static volatile uint64_t sim_delay_end = 0;
int sim_waiting_for_sender(void)
{
  /* a dwell's end: the clock waits until GRBL's main loop has seen it */
  if (sim_delaying) { return sim.masterclock >= sim_delay_end; }
  if (sim_synchronizing || plan_check_full_buffer()) { return 0; }
  /* bytes GRBL has received and not read: its main loop reads them before the next comes */
  if (serial_rx_buffer_head != serial_rx_buffer_tail) { simulate_write_interrupt(); return 1; }
  if (sys.state != STATE_CYCLE) { return 0; }
  simulate_write_interrupt();
  return !in_fill() && !in_eof;
}

/* GRBL's delays (dwell G4) on the simulated clock, which stops at their end until the main
   loop has seen it; on the clock's own thread (a stepper interrupt's delay) none, as the
   unchanged simulator's clock stands still there too */
static void wait_ticks(uint64_t ticks)
{
  uint64_t end = sim.masterclock + ticks;
  if (sim_in_clock_thread) { return; }
  sim_delay_end = end;
  sim_delaying = 1;
  while (*(volatile uint64_t *)&sim.masterclock < end && sim.exit != exit_OK) { platform_sleep(0); }
  sim_delaying = 0;
}
void _delay_ms(int i) { wait_ticks((uint64_t)i * (F_CPU / 1000)); }
void _delay_us(int i) { wait_ticks((uint64_t)i * (F_CPU / 1000000)); }
C
# the timers' side: how many ticks from now change nothing (no counter reaches a compare
# value, an overflow or a rollover, and no interrupt is pending); they are counted at once
intr=$b/grbl-sim/avr/interrupt.c
sed -i 's/\r$//' "$intr"
cat >>"$intr" <<'C'

/* millpath's GRBL oracle (tests/grbl/build_sim.sh): ticks, at most `limit`, after which the
   timers are as `limit` single ticks of timer_interrupts() would leave them, with nothing
   fired on the way; sim_count_ticks() then counts them. */
static uint32_t until_match(uint16_t target, uint16_t tcnt, uint16_t bitmask)
{
  uint32_t d = (uint16_t)(target - tcnt) & bitmask;
  return d ? d : (uint32_t)bitmask + 1;
}
uint64_t sim_quiet_ticks(uint64_t limit)
{
  int i;
  for (i = 0; i < SIM_N_TIMERS && limit > 0; i++) {
    uint8_t cs = io.tccrb[i] & 7, flags = io.tifr[i];
    uint16_t bitmask = timer_bitdepth[i], tcnt = io.tcnt[i];
    uint64_t inc = (uint64_t)sim_scaling[cs], p = io.prescaler, steps = 1u << 30, k;
    int ctc;
    if ((flags & (1 << SIM_ROLL)) || (compa_vect[i] && (flags & (1 << SIM_OCA))) ||
        (compb_vect[i] && (flags & (1 << SIM_OCB))) || (ovf_vect[i] && (flags & (1 << SIM_TOV)))) {
      return 0; /* an interrupt waits, or a rollover is due */
    }
    if (!inc) { continue; } /* stopped */
    if (i == 0 || i == 2) { ctc = sim_wgm_3[((io.tccrb[i] & 0x08) >> 1) | (io.tccra[i] & 3)] == wgm_CTC; }
    else { ctc = sim_wgm_4[((io.tccrb[i] & 0x18) >> 1) | (io.tccra[i] & 3)] == wgm_CTC; }
    if (ctc) { steps = until_match(io.ocra[i], tcnt, bitmask); }
    else if (sim_wgm_3[((io.tccrb[i] & 0x08) >> 1) | (io.tccra[i] & 3)] == wgm_NORMAL && (i == 0 || i == 2)) { steps = until_match(0, tcnt, bitmask); }
    else if (i == 1 && sim_wgm_4[((io.tccrb[i] & 0x18) >> 1) | (io.tccra[i] & 3)] == wgm_NORMAL) { steps = until_match(0, tcnt, bitmask); }
    if (io.timsk[i] & (1 << SIM_OCA)) { uint32_t d = until_match(io.ocra[i], tcnt, bitmask); if (d < steps) steps = d; }
    if (io.timsk[i] & (1 << SIM_OCB)) { uint32_t d = until_match(io.ocrb[i], tcnt, bitmask); if (d < steps) steps = d; }
    if (io.timsk[i] & (1 << SIM_OCC)) { uint32_t d = until_match(io.ocrc[i], tcnt, bitmask); if (d < steps) steps = d; }
    /* the counter's (steps)th increment comes at tick (p / inc + steps) * inc - p */
    k = (p / inc + steps) * inc - p - 1;
    if (k < limit) { limit = k; }
  }
  return limit;
}
void sim_count_ticks(uint64_t ticks)
{
  int i;
  uint64_t p = io.prescaler;
  for (i = 0; i < SIM_N_TIMERS; i++) {
    uint64_t inc = (uint64_t)sim_scaling[io.tccrb[i] & 7];
    if (inc) { io.tcnt[i] = (uint16_t)(io.tcnt[i] + ((p + ticks) / inc - p / inc)) & timer_bitdepth[i]; }
  }
  io.prescaler = (uint16_t)(p + ticks);
}
C
bash "$b/build.sh" "$out"
