// Expedited SDO (CiA 301): the frame codec for both sides, and a client that runs one
// transfer at a time with a timeout. Values are up to 4 bytes, little-endian.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ugv/io/can_frame.hpp"

namespace ugv::canopen {

// Abort codes the client and our emulator use (CiA 301 table 22).
namespace abort_code {
inline constexpr uint32_t timeout = 0x05040000;
inline constexpr uint32_t bad_command = 0x05040001;
inline constexpr uint32_t unsupported_access = 0x06010000;
inline constexpr uint32_t write_only = 0x06010001;
inline constexpr uint32_t read_only = 0x06010002;
inline constexpr uint32_t no_object = 0x06020000;
inline constexpr uint32_t not_mappable = 0x06040041;
inline constexpr uint32_t mapping_too_long = 0x06040042;
inline constexpr uint32_t length_mismatch = 0x06070010;
inline constexpr uint32_t no_subindex = 0x06090011;
inline constexpr uint32_t value_range = 0x06090030;
inline constexpr uint32_t general = 0x08000000;
inline constexpr uint32_t device_state = 0x08000022;
}  // namespace abort_code

// One line naming an abort code ("0x06020000 object does not exist").
std::string describe_abort(uint32_t code);

struct SdoAddress
{
    uint16_t index = 0;
    uint8_t subindex = 0;
    bool operator==(const SdoAddress&) const = default;
};

// Client -> server (COB-ID 0x600 + node).
io::CanFrame encode_sdo_download(uint8_t node, SdoAddress at, uint32_t value, int size_bytes);
io::CanFrame encode_sdo_upload(uint8_t node, SdoAddress at);
// Either side may abort (client: 0x600 + node, server: 0x580 + node).
io::CanFrame encode_sdo_abort(uint32_t cob_id, SdoAddress at, uint32_t code);

// What a server received.
struct SdoRequest
{
    enum class Kind { download, upload, abort, unsupported };
    Kind kind = Kind::unsupported;
    SdoAddress at;
    uint32_t value = 0;  // download: the data; abort: the code
    int size = 0;        // download: bytes, 0 when the request did not indicate a size
};
std::optional<SdoRequest> decode_sdo_request(const io::CanFrame& frame, uint8_t node);

// Server -> client (COB-ID 0x580 + node).
io::CanFrame encode_sdo_download_ack(uint8_t node, SdoAddress at);
io::CanFrame encode_sdo_upload_reply(uint8_t node, SdoAddress at, uint32_t value, int size_bytes);

// What a client received.
struct SdoResponse
{
    enum class Kind { download_ack, upload_data, abort, unsupported };
    Kind kind = Kind::unsupported;
    SdoAddress at;
    uint32_t value = 0;  // upload_data: the data; abort: the code
    int size = 0;        // upload_data: bytes (4 when the server did not say)
};
std::optional<SdoResponse> decode_sdo_response(const io::CanFrame& frame, uint8_t node);

struct SdoResult
{
    bool ok = false;
    bool timed_out = false;
    uint32_t abort_code = 0;  // when the server aborted, or abort_code::timeout
    uint32_t value = 0;       // read data
};

// Runs queued expedited transfers one at a time (a server handles one at a time). A transfer
// that is not answered within timeout_us is retried `retries` times, then fails with
// timed_out; an abort fails it at once. Callbacks run from on_frame()/tick().
class SdoClient
{
public:
    using Callback = std::function<void(const SdoResult&)>;

    SdoClient(uint8_t node, int64_t timeout_us, int retries = 1);

    // extra_retries: more attempts than the client's own for this transfer (one that may be
    // repeated at will: a read, or writing a configuration value again, over a noisy line).
    void write(SdoAddress at, uint32_t value, int size_bytes, Callback done = {}, int extra_retries = 0);
    void read(SdoAddress at, Callback done, int extra_retries = 0);
    // Drops every queued and running transfer without calling back (re-initialisation).
    void clear();

    // Sends the next request when idle, and times out the running one.
    void tick(int64_t now_us, std::vector<io::CanFrame>& out);
    // True when the frame was an SDO response for this node.
    bool on_frame(const io::CanFrame& frame, int64_t now_us, std::vector<io::CanFrame>& out);

    bool idle() const { return !running_ && queue_.empty(); }
    std::size_t pending() const { return queue_.size() + (running_ ? 1 : 0); }
    uint64_t timeouts() const { return timeouts_; }
    uint64_t aborts() const { return aborts_; }

private:
    struct Transfer
    {
        bool is_write = false;
        SdoAddress at;
        uint32_t value = 0;
        int size = 0;
        Callback done;
        int attempts = 0;
        int extra_retries = 0;
    };
    void send(Transfer& t, int64_t now_us, std::vector<io::CanFrame>& out);
    void finish(const SdoResult& result);

    uint8_t node_;
    int64_t timeout_us_;
    int retries_;
    std::deque<Transfer> queue_;
    std::optional<Transfer> running_;
    int64_t sent_us_ = 0;
    uint64_t timeouts_ = 0;
    uint64_t aborts_ = 0;
};

}  // namespace ugv::canopen
