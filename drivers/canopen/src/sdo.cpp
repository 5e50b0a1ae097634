#include "ugv/canopen/sdo.hpp"

#include <cstdio>

#include "ugv/canopen/ids.hpp"

namespace ugv::canopen {
namespace {

// Command specifiers (byte 0).
constexpr uint8_t kUploadRequest = 0x40;
constexpr uint8_t kDownloadAck = 0x60;
constexpr uint8_t kAbort = 0x80;

io::CanFrame sdo_frame(uint32_t cob_id, uint8_t command, SdoAddress at, uint32_t value)
{
    io::CanFrame f;
    f.id = cob_id;
    f.dlc = 8;
    f.data[0] = command;
    f.data[1] = static_cast<uint8_t>(at.index & 0xFF);
    f.data[2] = static_cast<uint8_t>(at.index >> 8);
    f.data[3] = at.subindex;
    for (int i = 0; i < 4; ++i) f.data[static_cast<std::size_t>(4 + i)] = static_cast<uint8_t>(value >> (8 * i));
    return f;
}

SdoAddress address_of(const io::CanFrame& f)
{
    return SdoAddress{static_cast<uint16_t>(f.data[1] | (f.data[2] << 8)), f.data[3]};
}

uint32_t value_of(const io::CanFrame& f, int size)
{
    uint32_t v = 0;
    for (int i = 0; i < size; ++i) v |= static_cast<uint32_t>(f.data[static_cast<std::size_t>(4 + i)]) << (8 * i);
    return v;
}

// Expedited, size indicated: 0x23/0x27/0x2B/0x2F for 4/3/2/1 bytes (base | n << 2, n = 4 - size).
uint8_t expedited(uint8_t base, int size) { return static_cast<uint8_t>(base | ((4 - size) << 2) | 0x03); }

bool plain_frame(const io::CanFrame& f, uint32_t id)
{
    return f.id == id && !f.extended && !f.rtr && f.dlc == 8;
}

}  // namespace

std::string describe_abort(uint32_t code)
{
    const char* what = "unknown abort code";
    switch (code) {
    case abort_code::timeout: what = "SDO protocol timed out"; break;
    case abort_code::bad_command: what = "command specifier not valid"; break;
    case abort_code::unsupported_access: what = "unsupported access to an object"; break;
    case abort_code::write_only: what = "attempt to read a write-only object"; break;
    case abort_code::read_only: what = "attempt to write a read-only object"; break;
    case abort_code::no_object: what = "object does not exist"; break;
    case abort_code::not_mappable: what = "object cannot be mapped to the PDO"; break;
    case abort_code::mapping_too_long: what = "mapped objects exceed the PDO length"; break;
    case abort_code::length_mismatch: what = "data type does not match, length mismatch"; break;
    case abort_code::no_subindex: what = "sub-index does not exist"; break;
    case abort_code::value_range: what = "value range of parameter exceeded"; break;
    case abort_code::general: what = "general error"; break;
    case abort_code::device_state: what = "not possible in the present device state"; break;
    default: break;
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, "0x%08X %s", code, what);
    return buf;
}

io::CanFrame encode_sdo_download(uint8_t node, SdoAddress at, uint32_t value, int size_bytes)
{
    const int size = size_bytes < 1 ? 1 : (size_bytes > 4 ? 4 : size_bytes);
    const uint32_t masked = size == 4 ? value : (value & ((1u << (8 * size)) - 1u));
    return sdo_frame(kSdoRequestBase + node, expedited(0x20, size), at, masked);
}

io::CanFrame encode_sdo_upload(uint8_t node, SdoAddress at)
{
    return sdo_frame(kSdoRequestBase + node, kUploadRequest, at, 0);
}

io::CanFrame encode_sdo_abort(uint32_t cob_id, SdoAddress at, uint32_t code)
{
    return sdo_frame(cob_id, kAbort, at, code);
}

std::optional<SdoRequest> decode_sdo_request(const io::CanFrame& f, uint8_t node)
{
    if (!plain_frame(f, kSdoRequestBase + node)) return std::nullopt;
    SdoRequest r;
    r.at = address_of(f);
    const uint8_t cmd = f.data[0];
    const uint8_t ccs = cmd >> 5;  // client command specifier
    if (ccs == 1 && (cmd & 0x02)) {  // initiate download, expedited
        r.kind = SdoRequest::Kind::download;
        r.size = (cmd & 0x01) ? 4 - ((cmd >> 2) & 0x03) : 0;
        r.value = value_of(f, r.size == 0 ? 4 : r.size);
    } else if (ccs == 2) {
        r.kind = SdoRequest::Kind::upload;
    } else if (ccs == 4) {
        r.kind = SdoRequest::Kind::abort;
        r.value = value_of(f, 4);
    } else {
        r.kind = SdoRequest::Kind::unsupported;  // segmented or block transfers
    }
    return r;
}

io::CanFrame encode_sdo_download_ack(uint8_t node, SdoAddress at)
{
    return sdo_frame(kSdoResponseBase + node, kDownloadAck, at, 0);
}

io::CanFrame encode_sdo_upload_reply(uint8_t node, SdoAddress at, uint32_t value, int size_bytes)
{
    const int size = size_bytes < 1 ? 1 : (size_bytes > 4 ? 4 : size_bytes);
    const uint32_t masked = size == 4 ? value : (value & ((1u << (8 * size)) - 1u));
    return sdo_frame(kSdoResponseBase + node, expedited(0x40, size), at, masked);
}

std::optional<SdoResponse> decode_sdo_response(const io::CanFrame& f, uint8_t node)
{
    if (!plain_frame(f, kSdoResponseBase + node)) return std::nullopt;
    SdoResponse r;
    r.at = address_of(f);
    const uint8_t cmd = f.data[0];
    const uint8_t scs = cmd >> 5;  // server command specifier
    if (scs == 3) {
        r.kind = SdoResponse::Kind::download_ack;
    } else if (scs == 2 && (cmd & 0x02)) {  // expedited upload
        r.kind = SdoResponse::Kind::upload_data;
        r.size = (cmd & 0x01) ? 4 - ((cmd >> 2) & 0x03) : 4;
        r.value = value_of(f, r.size);
    } else if (scs == 4) {
        r.kind = SdoResponse::Kind::abort;
        r.value = value_of(f, 4);
    } else {
        r.kind = SdoResponse::Kind::unsupported;  // segmented upload: more than 4 bytes
    }
    return r;
}

SdoClient::SdoClient(uint8_t node, int64_t timeout_us, int retries)
    : node_(node), timeout_us_(timeout_us), retries_(retries)
{
}

void SdoClient::write(SdoAddress at, uint32_t value, int size_bytes, Callback done, int extra_retries)
{
    queue_.push_back(Transfer{true, at, value, size_bytes, std::move(done), 0, extra_retries});
}

void SdoClient::read(SdoAddress at, Callback done, int extra_retries)
{
    queue_.push_back(Transfer{false, at, 0, 0, std::move(done), 0, extra_retries});
}

void SdoClient::clear()
{
    queue_.clear();
    running_.reset();
}

void SdoClient::send(Transfer& t, int64_t now_us, std::vector<io::CanFrame>& out)
{
    out.push_back(t.is_write ? encode_sdo_download(node_, t.at, t.value, t.size) : encode_sdo_upload(node_, t.at));
    ++t.attempts;
    sent_us_ = now_us;
}

void SdoClient::finish(const SdoResult& result)
{
    Callback done = std::move(running_->done);
    running_.reset();
    if (done) done(result);
}

void SdoClient::tick(int64_t now_us, std::vector<io::CanFrame>& out)
{
    if (running_ && now_us - sent_us_ > timeout_us_) {
        ++timeouts_;
        if (running_->attempts <= retries_ + running_->extra_retries) {
            send(*running_, now_us, out);
        } else {
            // Tell the server we gave up, so a late reply cannot be taken for the next one.
            out.push_back(encode_sdo_abort(kSdoRequestBase + node_, running_->at, abort_code::timeout));
            SdoResult r;
            r.timed_out = true;
            r.abort_code = abort_code::timeout;
            finish(r);
        }
    }
    if (!running_ && !queue_.empty()) {
        running_ = std::move(queue_.front());
        queue_.pop_front();
        send(*running_, now_us, out);
    }
}

bool SdoClient::on_frame(const io::CanFrame& frame, int64_t now_us, std::vector<io::CanFrame>& out)
{
    const auto resp = decode_sdo_response(frame, node_);
    if (!resp) return false;
    if (!running_ || !(resp->at == running_->at)) return true;  // late or foreign reply: ignore
    SdoResult r;
    switch (resp->kind) {
    case SdoResponse::Kind::download_ack:
        r.ok = running_->is_write;
        if (!r.ok) r.abort_code = abort_code::bad_command;
        break;
    case SdoResponse::Kind::upload_data:
        r.ok = !running_->is_write;
        r.value = resp->value;
        if (!r.ok) r.abort_code = abort_code::bad_command;
        break;
    case SdoResponse::Kind::abort:
        ++aborts_;
        r.abort_code = resp->value;
        break;
    case SdoResponse::Kind::unsupported:
        // Segmented upload (more than 4 bytes): not needed for a drive; abort it.
        out.push_back(encode_sdo_abort(kSdoRequestBase + node_, running_->at, abort_code::bad_command));
        r.abort_code = abort_code::bad_command;
        break;
    }
    finish(r);
    tick(now_us, out);  // start the next transfer without waiting for the next tick
    return true;
}

}  // namespace ugv::canopen
