#include "ugv/daemon/daemon.hpp"

#include <malloc.h>
#include <poll.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>
#include <cmath>
#include <spdlog/fmt/fmt.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "status_message.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/host_clock.hpp"
#include "ugv/runtime/realtime.hpp"
#include "ugv/runtime/stop_signals.hpp"

namespace ugv::daemon {

struct Daemon::Timer
{
    int64_t period_us;
    int64_t next_us;
    std::function<void()> fn;
};

namespace {

[[noreturn]] void exit_config_error(const std::string& line)
{
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
    std::_Exit(2);
}

int8_t wire_state(State s)
{
    switch (s) {
    case State::starting: return ugv::daemon_status_t::STATE_STARTING;
    case State::running: return ugv::daemon_status_t::STATE_RUNNING;
    case State::degraded: return ugv::daemon_status_t::STATE_DEGRADED;
    case State::fault: return ugv::daemon_status_t::STATE_FAULT;
    case State::stopping: return ugv::daemon_status_t::STATE_STOPPING;
    }
    return ugv::daemon_status_t::STATE_FAULT;
}

const char* state_name(State s)
{
    switch (s) {
    case State::starting: return "STARTING";
    case State::running: return "RUNNING";
    case State::degraded: return "DEGRADED";
    case State::fault: return "FAULT";
    case State::stopping: return "STOPPING";
    }
    return "?";
}

}  // namespace

Daemon::Daemon(Options options, int argc, char** argv) : options_(std::move(options))
{
    // A ConfigError thrown by a daemon's own config reads (before start()) escapes main():
    // turn it into the one-line message and exit status 2 instead of an abort.
    std::set_terminate([] {
        if (auto e = std::current_exception()) {
            try {
                std::rethrow_exception(e);
            } catch (const runtime::ConfigError& ce) {
                exit_config_error(ce.what());
            } catch (const std::exception& other) {
                std::fprintf(stderr, "fatal: %s\n", other.what());
            } catch (...) {
            }
        }
        std::abort();
    });
    std::string config_path = options_.default_config;
    CLI::App app{options_.name + ": a daemon of the ugv perception stack"};
    app.add_option("-c,--config", config_path, "TOML configuration file");
    app.add_option("--lcm-url", lcm_url_, "LCM URL (default: LCM_DEFAULT_URL, else udpm ttl=0)");
    app.add_option("--log-level", log_level_, "trace, debug, info, warn, error")
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
    app.add_option("--instance", instance_, "instance name (e.g. front), reported in status");
    app.add_flag("--print-config", print_config_, "print the effective configuration and exit");
    app.set_version_flag("--version", options_.name + " " + UGV_VERSION);
    if (options_.processing) {
        app.add_option("--replay", replay_path_, "read inputs from this LCM log, as fast as possible")
            ->check(CLI::ExistingFile);
        app.add_option("--out", out_path_, "with --replay: write outputs to this LCM log");
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        std::exit(app.exit(e));
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        std::exit(2);
    }
    if (!replay_path_.empty() && out_path_.empty()) exit_config_error(options_.name + ": --replay needs --out");
    if (replay_path_.empty() && !out_path_.empty()) exit_config_error(options_.name + ": --out needs --replay");
    replaying_ = !replay_path_.empty();
    io::clock_test_offset_us();  // a bad UGV_CLOCK_OFFSET_S exits 2 with its line, before anything runs

    auto logger = spdlog::stderr_color_mt(options_.name);
    spdlog::set_default_logger(logger);
    spdlog::set_pattern("%^%l%$ %v");  // journald adds time and name
    spdlog::set_level(spdlog::level::from_str(log_level_.empty() ? "info" : log_level_));

    try {
        if (config_path.empty())
            config_ = std::make_unique<runtime::Config>(runtime::Config::empty());
        else if (access(config_path.c_str(), F_OK) != 0 && config_path == options_.default_config)
            config_ = std::make_unique<runtime::Config>(runtime::Config::empty(config_path + " (absent: defaults)"));
        else
            config_ = std::make_unique<runtime::Config>(runtime::Config::load(config_path));
        std::string def_status = options_.status_channel;
        if (def_status.empty()) {
            def_status = "STATUS_" + options_.name.substr(options_.name.rfind('-') + 1);
            for (auto& c : def_status) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        }
        status_channel_ = config_->get_channel("status_channel", def_status);
        bus_batch_us_ = config_->get_int("bus_batch_ms", options_.bus_batch_ms, 0, 100) * 1000;
        startup_timeout_us_ = std::llround(config_->get_double("startup_timeout_s", 30.0, 1.0, 3600.0) * 1e6);
    } catch (const runtime::ConfigError& e) {
        exit_config_error(e.what());
    }
}

Daemon::~Daemon() = default;

void Daemon::start()
{
    runtime::RealtimeOptions rt;
    bus::LiveOptions live;
    try {
        live.max_message_bytes = static_cast<std::size_t>(config_->get_int(
            "bus_max_message_bytes", static_cast<int64_t>(bus::kDefaultMaxMessageBytes), 65536, 64 << 20));
        runtime::Config r = config_->section("realtime");
        rt.lock_memory = r.get_bool("lock_memory", false);
        rt.fifo_priority = static_cast<int>(r.get_int("fifo_priority", 0, 0, 99));
        for (const double c : r.get_doubles("cpus", {}, 0, 0, 1023)) rt.cpus.push_back(static_cast<int>(c));
        config_->finish();
    } catch (const runtime::ConfigError& e) {
        exit_config_error(e.what());
    }
    if (print_config_) {
        std::fputs(config_->effective_toml().c_str(), stdout);
        std::exit(0);
    }
    for (const auto& w : runtime::apply_realtime(rt)) spdlog::warn("{}", w);
    // Large messages (maps, clouds: 0.1-1 MB, several copies each) from a heap that keeps its
    // pages, not from a fresh mmap or a regrown heap each time: their page faults were a third
    // of ugv-traverse's CPU and a sixth of ugv-foxglove's (perf).
    mallopt(M_MMAP_THRESHOLD, 16 << 20);
    mallopt(M_TRIM_THRESHOLD, 32 << 20);

    try {
        if (replaying_) {
            in_ = bus::open_log_replay(replay_path_);
            bus::Bus* in = in_.get();
            out_log_ = bus::open_log_writer(out_path_, [in] { return in->now_utime(); });
            out_ = out_log_.get();
        } else {
            in_ = bus::open_live(lcm_url_.empty() ? bus::default_url() : lcm_url_, live);
            out_ = in_.get();  // one LCM instance both ways
        }
    } catch (const bus::BusError& e) {
        exit_config_error(options_.name + ": " + e.what());
    }
    runtime::install_stop_signals();
    start_us_ = io::monotonic_us();
    spdlog::info("{} {} started on {}", options_.name, UGV_VERSION, in_->describe());
    if (const int64_t off = io::clock_test_offset_us(); off != 0)
        spdlog::warn("{} = {:.6f} s: every time stamp of this process is shifted (a test aid, docs/time.md)",
                     io::kClockOffsetEnv, static_cast<double>(off) * 1e-6);
}

void Daemon::set_state(State state, const std::string& error)
{
    std::lock_guard<std::mutex> lock(error_mutex_);
    requested_.store(state);
    if (!error.empty()) reason_ = error;
    // These need no output to be true: reported at once. RUNNING waits for the output
    // (update_state), so a session that says "streaming" while nothing comes out is not.
    if (state == State::degraded || state == State::fault) report(state, reason_);
    if (state == State::stopping) report(state, error);
}

void Daemon::report(State s, const std::string& why)
{
    const State old = state_.exchange(s);
    if (!why.empty()) last_error_ = why;
    if (old != s) spdlog::info("state {} -> {}{}{}", state_name(old), state_name(s), why.empty() ? "" : ": ", why);
}

void Daemon::declare_output(std::string what, int64_t stall_us)
{
    output_ = std::move(what);
    health_timeout_us_ = stall_us;
}

void Daemon::mark_output() { prev_alive_us_.store(last_alive_us_.exchange(io::monotonic_us())); }

void Daemon::update_state()
{
    std::lock_guard<std::mutex> lock(error_mutex_);
    const State cur = state_.load();
    const State want = requested_.load();
    // STOPPING is final; DEGRADED and FAULT were reported by set_state with their reason.
    if (cur == State::stopping || want == State::degraded || want == State::fault || want == State::stopping) return;
    const int64_t now = io::monotonic_us();
    const int64_t last = last_alive_us_.load();
    const int64_t prev = prev_alive_us_.load();
    const bool fresh = last != 0 && now - last <= health_timeout_us_;
    // Hysteresis: RUNNING is entered on two marks within the stall time and left only when
    // none came for the stall time, so a trickle among garbage does not flap the state.
    const bool flowing = fresh && prev != 0 && last - prev <= health_timeout_us_;
    if (cur == State::running ? fresh : flowing) {
        if (cur != State::running) reason_.clear();  // whatever it was no longer holds
        report(State::running, "");
        return;
    }
    const std::string stall = fmt::format("{:.1f} s", static_cast<double>(health_timeout_us_) * 1e-6);
    if (cur == State::running) {
        report(State::degraded, "no " + output_ + " for " + stall + (reason_.empty() ? "" : " (" + reason_ + ")"));
        return;
    }
    if (cur == State::starting && now - start_us_ >= startup_timeout_us_) {
        report(State::degraded, fmt::format("no {} within startup_timeout_s = {:g} s of start{}{}", output_,
                                            static_cast<double>(startup_timeout_us_) * 1e-6, reason_.empty() ? "" : ": ",
                                            reason_));
        // Up and saying what is wrong: systemd's start timeout would only restart it, and the
        // watchdog now watches the main loop.
        if (!ready_sent_.exchange(true)) notifier_.ready();
    }
}

void Daemon::ready()
{
    {
        std::lock_guard<std::mutex> lock(error_mutex_);
        if (requested_.load() != State::stopping) requested_.store(State::running);
    }
    if (!ready_sent_.exchange(true)) notifier_.ready();
}

void Daemon::notify_status(const std::string& line)
{
    notifier_.status(line);
    spdlog::debug("status: {}", line);
}

void Daemon::add_fd(int fd, std::function<void()> on_readable) { fds_.emplace_back(fd, std::move(on_readable)); }

void Daemon::remove_fd(int fd)
{
    std::erase_if(fds_, [fd](const auto& p) { return p.first == fd; });
}

void Daemon::add_timer(int64_t period_us, std::function<void()> fn)
{
    timers_.push_back(std::make_unique<Timer>(Timer{period_us, io::monotonic_us() + period_us, std::move(fn)}));
}

bool Daemon::stop_requested() const { return runtime::stop_requested() || stop_flag_.load(); }

void Daemon::request_stop()
{
    stop_flag_.store(true);
}

void Daemon::publish_status()
{
    update_state();
    std::string err;
    {
        std::lock_guard<std::mutex> lock(error_mutex_);
        err = last_error_;
    }
    auto counters = counters_.snapshot();
    // The bus's counters, prefixed bus_; publishing goes through out_ (the --out log in a replay).
    bus::BusCounters bus_counters = in_->counters();
    bus_counters.publish_failures = out_->counters().publish_failures;
    bus_counters.visit([&counters](std::string_view name, auto value) {
        counters.emplace_back("bus_" + std::string(name), static_cast<int64_t>(value));
    });
    // The host clock's synchronisation (docs/time.md), read each second: chrony may lose it.
    runtime::read_host_clock().visit([&counters](std::string_view name, int64_t value) {
        counters.emplace_back(std::string(name), value);
    });
    const auto msg = make_status_message(io::now_utime(), status_seq_++, options_.name, instance_,
                                         wire_state(state_.load()), err, io::monotonic_us() - start_us_, counters);
    bus::publish(*out_, status_channel_, msg);
}

void Daemon::on_watchdog()
{
    // Ping while RUNNING with fresh data, and while DEGRADED for a known reason: then the
    // daemon is recovering (reopening a device with back-off, dead-reckoning through a GPS
    // outage), or, for a processing daemon, waiting for inputs a restart would not bring back;
    // a restart would only lose its state and, repeated, trip the start limit. What the
    // watchdog is for -- a hung main loop, or a device session stuck without a word (its
    // output stopped while it said nothing) -- stops the pings.
    const State s = state_.load();
    const bool fresh = io::monotonic_us() - last_alive_us_.load() <= health_timeout_us_;
    bool explained = options_.processing;
    {
        std::lock_guard<std::mutex> lock(error_mutex_);
        explained = explained || requested_.load() == State::degraded || !reason_.empty();
    }
    if ((s == State::running && fresh) || (s == State::degraded && explained)) notifier_.watchdog();
}

namespace {
constexpr int64_t kTimerSlackUs = 500;
}  // namespace

int Daemon::run()
{
    if (!in_) {
        spdlog::critical("Daemon::run() called before start()");
        return 1;
    }
    if (replaying_) {
        while (!stop_requested() && in_->handle(0) == bus::HandleResult::handled) {
        }
        spdlog::info("replay done: {} messages dispatched, {} undecodable", in_->counters().received,
                     in_->counters().decode_failures);
        return 0;
    }
    add_timer(1'000'000, [this] { publish_status(); });
    add_timer(250'000, [this] { update_state(); });
    const int64_t wd = notifier_.watchdog_interval_us();
    if (wd > 0) add_timer(wd, [this] { on_watchdog(); });
    // Batched: a timer drains the bus instead of a wake-up per datagram (Options::bus_batch_ms).
    const bool batched = bus_batch_us_ > 0 && in_->fd() >= 0;
    if (batched)
        add_timer(bus_batch_us_, [this] {
            // Each handle() is a bounded read; under a flood, stop after a quarter of the
            // period so the daemon's own timers keep theirs.
            const int64_t until = io::monotonic_us() + std::max<int64_t>(bus_batch_us_ / 4, 1000);
            for (int k = 0; k < 10'000 && in_->handle(0) == bus::HandleResult::handled && io::monotonic_us() < until; ++k) {
            }
        });
    publish_status();

    const int stop_fd = runtime::install_stop_signals();
    std::vector<pollfd> pfds;
    while (!stop_requested()) {
        pfds.clear();
        pfds.push_back({stop_fd, POLLIN, 0});
        pfds.push_back({batched ? -1 : in_->fd(), POLLIN, 0});
        for (const auto& [fd, fn] : fds_) pfds.push_back({fd, POLLIN, 0});
        int64_t now = io::monotonic_us();
        int64_t wait_us = 100'000;
        for (const auto& t : timers_) wait_us = std::min(wait_us, std::max<int64_t>(0, t->next_us - now));
        ::poll(pfds.data(), pfds.size(), static_cast<int>((wait_us + 999) / 1000));
        if (pfds[1].revents & POLLIN) in_->handle(0);
        for (std::size_t k = 2; k < pfds.size(); ++k) {
            if (pfds[k].revents == 0) continue;
            // The callback may remove fds: look the fd up again rather than index fds_.
            const int fd = pfds[k].fd;
            for (auto& [f, fn] : fds_)
                if (f == fd) {
                    auto copy = fn;
                    copy();
                    break;
                }
        }
        now = io::monotonic_us();
        for (auto& t : timers_) {
            // Timer slack: a timer due within kTimerSlackUs runs with the one that woke us, so
            // timers of one period (a control tick and a bus drain) share a wake-up.
            if (now + kTimerSlackUs < t->next_us) continue;
            t->next_us += t->period_us;
            if (t->next_us < now) t->next_us = now + t->period_us;  // we were late: do not burst
            t->fn();
        }
    }
    set_state(State::stopping);
    notifier_.stopping();
    publish_status();
    spdlog::info("stopping");
    return 0;
}

}  // namespace ugv::daemon
