// Test support: temporary folders and child processes (the real daemons and emulators that
// integration tests start). Header-only so every test executable can use it.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace ugv::test {

// A fresh folder under /tmp, removed when the object goes.
class TempDir
{
public:
    TempDir()
    {
        std::string tmpl = (std::filesystem::temp_directory_path() / "ugv-test-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
        path_ = tmpl;
    }
    ~TempDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& path() const { return path_; }
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

// The path of one of our programs (tests run with UGV_BIN_DIR set by CTest).
inline std::string bin(const std::string& name)
{
    const char* dir = std::getenv("UGV_BIN_DIR");
    return std::string(dir ? dir : UGV_BINARY_DIR "/bin") + "/" + name;
}

inline std::string read_file(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_file(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

// A child process with stdout and stderr in files; killed (SIGKILL) if still running when
// the object goes.
class Process
{
public:
    Process(std::vector<std::string> argv, const std::string& out_path, const std::string& err_path,
            std::vector<std::string> extra_env = {})
        : out_path_(out_path), err_path_(err_path)
    {
        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_addopen(&fa, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_addopen(&fa, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        std::vector<char*> args;
        for (auto& a : argv) args.push_back(a.data());
        args.push_back(nullptr);
        std::vector<std::string> env_store;
        for (char** e = environ; *e; ++e) env_store.emplace_back(*e);
        for (auto& e : extra_env) env_store.push_back(e);
        std::vector<char*> env;
        for (auto& e : env_store) env.push_back(e.data());
        env.push_back(nullptr);
        const int rc = posix_spawn(&pid_, args[0], &fa, nullptr, args.data(), env.data());
        posix_spawn_file_actions_destroy(&fa);
        if (rc != 0) throw std::runtime_error("cannot start " + argv[0]);
    }
    ~Process()
    {
        if (running()) {
            ::kill(pid_, SIGKILL);
            wait_exit(5.0);
        }
    }
    Process(const Process&) = delete;
    Process& operator=(const Process&) = delete;

    pid_t pid() const { return pid_; }
    bool running()
    {
        if (exited_) return false;
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
            record(status);
            return false;
        }
        return true;
    }
    void signal(int sig) { ::kill(pid_, sig); }
    // Waits up to timeout_s for the exit; returns the exit code (128+signal when killed),
    // or -1 if it is still running.
    int wait_exit(double timeout_s)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < end) {
            if (!running()) return code_;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return running() ? -1 : code_;
    }
    std::string out() const { return read_file(out_path_); }
    std::string err() const { return read_file(err_path_); }

private:
    void record(int status)
    {
        exited_ = true;
        code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    pid_t pid_ = -1;
    bool exited_ = false;
    int code_ = -1;
    std::string out_path_, err_path_;
};

// Runs a command to completion (bounded) and returns its exit code; output in the files.
inline int run(std::vector<std::string> argv, const std::string& out_path, const std::string& err_path,
               double timeout_s = 60.0)
{
    Process p(std::move(argv), out_path, err_path);
    return p.wait_exit(timeout_s);
}

// Polls pred every 10 ms until it is true or timeout_s passes.
template <typename Pred>
bool wait_until(Pred pred, double timeout_s)
{
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < end) {
        if (pred()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return pred();
}

// An LCM URL on a port of the test's own (ttl=0: this host only).
inline std::string lcm_url(int port) { return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0"; }

}  // namespace ugv::test
