// The stop signals every daemon, emulator and tool shares: SIGINT and SIGTERM set a flag and
// write a byte to a non-blocking self-pipe; SIGPIPE is ignored (a reader that goes away must
// not kill the writer). The handlers are installed without SA_RESTART, so a blocking call
// (poll, read, sleep) returns EINTR and the caller's loop sees the flag at once.
//
//   const int stop_fd = ugv::runtime::install_stop_signals();
//   while (!ugv::runtime::stop_requested()) { poll({stop_fd, the device's fd, ...}); ... }
#pragma once

namespace ugv::runtime {

// Creates the pipe on the first call and (re)installs the handlers on every call, so calling
// it twice is harmless. Returns the pipe's read end for poll() (readable once a stop signal
// came; nobody drains it), or -1 if no pipe could be made (the flag still works).
int install_stop_signals();

// True once SIGINT or SIGTERM arrived (after install_stop_signals()). Async-signal-safe and
// thread-safe.
bool stop_requested();

// The pipe's read end; -1 before install_stop_signals().
int stop_signal_fd();

}  // namespace ugv::runtime
