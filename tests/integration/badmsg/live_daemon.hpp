// A processing daemon running live on this test's own LCM port, as the bad-message tests
// drive it: publish typed messages or raw bytes on its inputs, keep its latest STATUS
// counters, hand its outputs to a callback.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ugv/daemon_status_t.hpp>

#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

namespace ugv::test {

class LiveDaemon
{
public:
    using Output = std::function<void(const uint8_t* data, std::size_t size)>;

    // Starts `program` with `config_text` as its config on udpm port `port`; status_channel
    // is where its daemon_status_t goes.
    LiveDaemon(const std::string& program, const std::string& config_text, int port, const std::string& status_channel);

    // Calls on_output with the bytes of every message on channel.
    void on(const std::string& channel, Output on_output);
    // Calls on_message with every message on channel that decodes as a whole T.
    template <typename T>
    void on_decoded(const std::string& channel, std::function<void(const T&)> on_message)
    {
        on(channel, [on_message = std::move(on_message)](const uint8_t* data, std::size_t size) {
            T m{};
            if (m.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size)) on_message(m);
        });
    }
    // Waits (handling traffic) until the first status message, up to timeout_s.
    bool wait_up(double timeout_s);
    // Handles traffic for seconds.
    void pump(double seconds);

    template <typename T>
    void publish(const std::string& channel, const T& msg)
    {
        publish_bytes(channel, encoded(msg));
    }
    void publish_bytes(const std::string& channel, const std::vector<uint8_t>& bytes);

    // The counter from the latest status (-1 before any status names it), and how many
    // statuses arrived so far.
    int64_t counter(const std::string& name) const;
    int statuses() const { return statuses_; }
    // The state (daemon_status_t::STATE_*, -1 before any status) and last_error of the latest status.
    int state() const { return state_; }
    const std::string& last_error() const { return last_error_; }
    pid_t pid() const { return process_->pid(); }
    bool running() { return process_->running(); }
    std::string stderr_text() { return process_->err(); }
    int stop();  // SIGTERM, then the exit code

private:
    struct Handler
    {
        Output fn;
        void handle(const lcm::ReceiveBuffer* rbuf, const std::string&)
        {
            fn(static_cast<const uint8_t*>(rbuf->data), rbuf->data_size);
        }
    };

    TempDir dir_;
    lcm::LCM bus_;
    std::vector<std::unique_ptr<Handler>> handlers_;
    std::map<std::string, int64_t> counters_;
    int statuses_ = 0;
    int state_ = -1;
    std::string last_error_;
    std::unique_ptr<Process> process_;
};

}  // namespace ugv::test
