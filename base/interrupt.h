// Ctrl-C and `kill` as a request to stop cleanly. Once catch_interrupts() is called, the first
// SIGINT, SIGTERM or SIGHUP is only recorded: the loops that wait on workers see it (their waits
// return early, as the handler does not restart system calls), end their workers, remove their
// temporary folders and return, and the command exits with 128 + the signal. A second one ends
// the process at once, as if nothing had caught it. A signal the process was started ignoring
// (nohup) stays ignored.
#pragma once

namespace xshade {

void catch_interrupts();
// The default action again, for a process forked from one that catches them (a worker).
void stop_catching_interrupts();
// The signal that asked this process to stop, or 0.
int interrupt_signal();

}  // namespace xshade
