#include "live_daemon.hpp"

#include <csignal>

namespace ugv::test {

LiveDaemon::LiveDaemon(const std::string& program, const std::string& config_text, int port,
                       const std::string& status_channel)
    : bus_(lcm_url(port))
{
    if (!bus_.good()) throw std::runtime_error("cannot open " + lcm_url(port));
    on(status_channel, [this](const uint8_t* data, std::size_t size) {
        daemon_status_t s;
        if (s.decode(data, 0, static_cast<int>(size)) != static_cast<int>(size)) return;
        ++statuses_;
        state_ = s.state;
        last_error_ = s.last_error;
        for (int k = 0; k < s.ncounters; ++k) {
            counters_[s.counter_names[static_cast<std::size_t>(k)]] = s.counter_values[static_cast<std::size_t>(k)];
        }
    });
    const std::string config = dir_ / "daemon.toml";
    write_file(config, config_text);
    process_ = std::make_unique<Process>(
        std::vector<std::string>{bin(program), "--config", config, "--lcm-url", lcm_url(port)}, dir_ / "out.txt",
        dir_ / "err.txt");
}

void LiveDaemon::on(const std::string& channel, Output on_output)
{
    handlers_.push_back(std::make_unique<Handler>(Handler{std::move(on_output)}));
    bus_.subscribe(channel, &Handler::handle, handlers_.back().get());
}

bool LiveDaemon::wait_up(double timeout_s)
{
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (statuses_ == 0 && std::chrono::steady_clock::now() < end && process_->running()) bus_.handleTimeout(50);
    return statuses_ > 0;
}

void LiveDaemon::pump(double seconds)
{
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) bus_.handleTimeout(2);
}

void LiveDaemon::publish_bytes(const std::string& channel, const std::vector<uint8_t>& bytes)
{
    bus_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

int64_t LiveDaemon::counter(const std::string& name) const
{
    const auto it = counters_.find(name);
    return it == counters_.end() ? -1 : it->second;
}

int LiveDaemon::stop()
{
    process_->signal(SIGTERM);
    return process_->wait_exit(10.0);
}

}  // namespace ugv::test
