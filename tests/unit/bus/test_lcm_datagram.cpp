// LCM's udpm datagrams decoded from hand-made bytes, and fragment reassembly.
#include <catch2/catch.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "ugv/bus/lcm_datagram.hpp"

using namespace ugv::bus::detail;

namespace {

void put32(std::vector<uint8_t>& b, uint32_t v)
{
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<uint8_t>(v >> s));
}
void put16(std::vector<uint8_t>& b, uint16_t v)
{
    b.push_back(static_cast<uint8_t>(v >> 8));
    b.push_back(static_cast<uint8_t>(v));
}
void put(std::vector<uint8_t>& b, const std::string& s, bool nul)
{
    b.insert(b.end(), s.begin(), s.end());
    if (nul) b.push_back(0);
}

std::vector<uint8_t> short_datagram(uint32_t seq, const std::string& channel, const std::string& payload)
{
    std::vector<uint8_t> b;
    put32(b, 0x4c433032);
    put32(b, seq);
    put(b, channel, true);
    put(b, payload, false);
    return b;
}

std::vector<uint8_t> fragment(uint32_t seq, uint32_t size, uint32_t offset, uint16_t no, uint16_t count,
                              const std::string& channel, const std::string& payload)
{
    std::vector<uint8_t> b;
    put32(b, 0x4c433033);
    put32(b, seq);
    put32(b, size);
    put32(b, offset);
    put16(b, no);
    put16(b, count);
    if (no == 0) put(b, channel, true);
    put(b, payload, false);
    return b;
}

LcmDatagram parse(const std::vector<uint8_t>& b) { return parse_lcm_datagram(b.data(), b.size()); }

constexpr int64_t kNow = 1'700'000'000'000'000;

std::string text(const LcmReassembler::Message& m) { return std::string(m.payload.begin(), m.payload.end()); }

}  // namespace

TEST_CASE("lcm datagram: a short message gives its sequence, channel and payload")
{
    const auto b = short_datagram(0x01020304, "POSE", "abc");
    // The header bytes as liblcm writes them: "LC02", then the sequence big-endian.
    REQUIRE(b.size() == 8 + 5 + 3);
    CHECK(b[0] == 'L');
    CHECK(b[3] == '2');
    CHECK(b[4] == 0x01);
    const LcmDatagram d = parse(b);
    REQUIRE(d.kind == LcmDatagram::Kind::short_message);
    CHECK(d.sequence == 0x01020304u);
    CHECK(d.channel == "POSE");
    CHECK(std::string(reinterpret_cast<const char*>(d.payload), d.payload_size) == "abc");
    CHECK(parse(short_datagram(1, "EMPTY", "")).payload_size == 0);
}

TEST_CASE("lcm datagram: what is not a well-formed LCM datagram is invalid")
{
    CHECK(parse({}).kind == LcmDatagram::Kind::invalid);
    CHECK(parse({'L', 'C', '0', '2', 0, 0, 0}).kind == LcmDatagram::Kind::invalid);  // 7 bytes
    auto wrong_magic = short_datagram(1, "A", "x");
    wrong_magic[3] = '4';
    CHECK(parse(wrong_magic).kind == LcmDatagram::Kind::invalid);
    CHECK(parse(short_datagram(1, "", "x")).kind == LcmDatagram::Kind::invalid);  // empty channel
    // No NUL within liblcm's 63-character limit.
    CHECK(parse(short_datagram(1, std::string(63, 'C'), "")).kind == LcmDatagram::Kind::short_message);
    CHECK(parse(short_datagram(1, std::string(64, 'C'), "")).kind == LcmDatagram::Kind::invalid);
    auto no_nul = short_datagram(1, "ABC", "");
    no_nul.pop_back();
    CHECK(parse(no_nul).kind == LcmDatagram::Kind::invalid);
}

TEST_CASE("lcm datagram: fragment headers, and fragments outside their message are invalid")
{
    // The datagram's bytes must outlive it: channel and payload point into them.
    const auto first_bytes = fragment(9, 10, 0, 0, 2, "MAP", "01234");
    const LcmDatagram first = parse(first_bytes);
    REQUIRE(first.kind == LcmDatagram::Kind::fragment);
    CHECK(first.sequence == 9u);
    CHECK(first.message_size == 10u);
    CHECK(first.fragment_no == 0);
    CHECK(first.fragment_count == 2);
    CHECK(first.channel == "MAP");
    CHECK(first.payload_size == 5);
    const auto second_bytes = fragment(9, 10, 5, 1, 2, "", "56789");
    const LcmDatagram second = parse(second_bytes);
    REQUIRE(second.kind == LcmDatagram::Kind::fragment);
    CHECK(second.channel.empty());
    CHECK(second.offset == 5u);
    CHECK(*second.payload == '5');

    CHECK(parse(fragment(9, 10, 6, 1, 2, "", "56789")).kind == LcmDatagram::Kind::invalid);   // past the end
    CHECK(parse(fragment(9, 10, 5, 2, 2, "", "56789")).kind == LcmDatagram::Kind::invalid);   // no >= count
    CHECK(parse(fragment(9, 10, 5, 0, 0, "M", "56789")).kind == LcmDatagram::Kind::invalid);  // count 0
    CHECK(parse(fragment(9, 10, 3, 0, 2, "M", "56789")).kind == LcmDatagram::Kind::invalid);  // fragment 0 not at 0
    CHECK(parse(fragment(9, kLcmMaxMessageBytes + 1, 0, 0, 2000, "M", "x")).kind == LcmDatagram::Kind::invalid);
    // More than its fragments can carry: 2 fragments of at most 65535 bytes.
    CHECK(parse(fragment(9, 2 * 65535 + 1, 0, 0, 2, "M", "x")).kind == LcmDatagram::Kind::invalid);
    CHECK(parse(fragment(9, 2 * 65535, 0, 0, 2, "M", "x")).kind == LcmDatagram::Kind::fragment);
    auto short_header = fragment(9, 10, 5, 1, 2, "", "");
    short_header.resize(19);
    CHECK(parse(short_header).kind == LcmDatagram::Kind::invalid);
}

TEST_CASE("lcm reassembly: fragments in any order make the message once; duplicates are ignored")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 6, 2, 3, "", "ghi")), kNow, m));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 0, 0, 3, "MAP", "abc")), kNow, m));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 0, 0, 3, "MAP", "abc")), kNow, m));  // again
    REQUIRE(r.add_fragment(1, parse(fragment(4, 9, 3, 1, 3, "", "def")), kNow, m));
    CHECK(m.channel == "MAP");
    CHECK(text(m) == "abcdefghi");
    CHECK(r.counters().incomplete_messages == 0);
    CHECK(r.counters().invalid_datagrams == 0);
    // A late duplicate of a finished message starts a new one, which never completes.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 3, 1, 3, "", "def")), kNow, m));
}

TEST_CASE("lcm reassembly: a message on a channel nobody wants is followed to its end, not kept")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    const LcmReassembler::Wants wants = [](std::string_view channel) { return channel == "MAP"; };
    // Fragment 2 comes first and is held until fragment 0 names the channel.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 6, 2, 3, "", "ghi")), kNow, m, &wants));
    CHECK(r.bytes_held() > 0);
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 0, 0, 3, "OTHER", "abc")), kNow, m, &wants));
    CHECK(r.bytes_held() == 0);
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 3, 1, 3, "", "def")), kNow, m, &wants));
    CHECK(r.counters().unwanted_messages == 1);
    CHECK(r.counters().incomplete_messages == 0);
    CHECK(r.counters().invalid_datagrams == 0);
    // The sender's next message, wanted, is made as before.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(5, 6, 0, 0, 2, "MAP", "ABC")), kNow, m, &wants));
    REQUIRE(r.add_fragment(1, parse(fragment(5, 6, 3, 1, 2, "", "DEF")), kNow, m, &wants));
    CHECK(m.channel == "MAP");
    CHECK(text(m) == "ABCDEF");
    // An unwanted message's fragments that do not tile it are invalid, as a kept one's.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(6, 9, 0, 0, 2, "OTHER", "abc")), kNow, m, &wants));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(6, 9, 3, 1, 2, "", "def")), kNow, m, &wants));
    CHECK(r.counters().invalid_datagrams == 1);
    CHECK(r.counters().unwanted_messages == 1);
    CHECK(r.bytes_held() == 0);
}

TEST_CASE("lcm reassembly: a new message from a sender abandons its unfinished one, and it is counted")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(7, parse(fragment(1, 6, 0, 0, 2, "A", "abc")), kNow, m));
    // Fragment 1 of message 1 was lost; message 2 begins.
    CHECK_FALSE(r.add_fragment(7, parse(fragment(2, 6, 0, 0, 2, "A", "ABC")), kNow, m));
    CHECK(r.counters().incomplete_messages == 1);
    REQUIRE(r.add_fragment(7, parse(fragment(2, 6, 3, 1, 2, "", "DEF")), kNow, m));
    CHECK(text(m) == "ABCDEF");
}

TEST_CASE("lcm reassembly: two senders interleaved are kept apart")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(5, 4, 0, 0, 2, "ONE", "ab")), kNow, m));
    CHECK_FALSE(r.add_fragment(2, parse(fragment(5, 4, 0, 0, 2, "TWO", "AB")), kNow, m));
    REQUIRE(r.add_fragment(2, parse(fragment(5, 4, 2, 1, 2, "", "CD")), kNow, m));
    CHECK(m.channel == "TWO");
    CHECK(text(m) == "ABCD");
    REQUIRE(r.add_fragment(1, parse(fragment(5, 4, 2, 1, 2, "", "cd")), kNow, m));
    CHECK(m.channel == "ONE");
    CHECK(text(m) == "abcd");
    CHECK(r.counters().incomplete_messages == 0);
}

TEST_CASE("lcm reassembly: fragments that contradict their message or do not tile it are invalid")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 6, 0, 0, 2, "A", "abc")), kNow, m));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 8, 3, 1, 2, "", "def")), kNow, m));  // another size
    CHECK(r.counters().invalid_datagrams == 1);
    // All fragments there, but only 5 of the 6 bytes: not handed out.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 6, 3, 1, 2, "", "de")), kNow, m));
    CHECK(r.counters().invalid_datagrams == 2);
    // Not LCM at all.
    const std::vector<uint8_t> junk{1, 2, 3, 4, 5, 6, 7, 8, 9};
    CHECK_FALSE(r.add_fragment(1, parse(junk), kNow, m));
    CHECK(r.counters().invalid_datagrams == 3);
}

TEST_CASE("lcm reassembly: a claimed size is never allocated; what it holds never exceeds what it received")
{
    // The attack of issue 23: headers of 20 bytes claiming a large message, from many senders.
    LcmReassembler r;  // defaults: 1 MiB per message
    LcmReassembler::Message m;
    const uint32_t big = 1000u << 10;  // within the limit
    for (uint64_t sender = 0; sender < 64; ++sender) {
        CHECK_FALSE(r.add_fragment(sender, parse(fragment(1, big, 65000, 1, 100, "", "")), kNow, m));
        CHECK(r.bytes_held() <= r.bytes_received());
    }
    // 32 senders in progress, each charged its header only; the 32 least recent evicted.
    CHECK(r.bytes_held() == 32 * kLcmFragmentHeaderBytes);
    CHECK(r.bytes_received() == 64 * 20);
    CHECK(r.counters().evicted_messages == 32);
    // A fragment with bytes is charged its bytes (its sender takes the least recent slot).
    CHECK_FALSE(r.add_fragment(99, parse(fragment(1, big, 0, 0, 100, "MAP", std::string(1000, 'x'))), kNow, m));
    CHECK(r.counters().evicted_messages == 33);
    CHECK(r.bytes_held() == 31 * kLcmFragmentHeaderBytes + 1000 + kLcmFragmentHeaderBytes);
    CHECK(r.bytes_held() <= r.bytes_received());
}

TEST_CASE("lcm reassembly: a message over max_message_bytes is refused and counted, one at the limit completes")
{
    ReassemblyLimits limits;
    limits.max_message_bytes = 100'000;
    LcmReassembler r(limits);
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(1, 100'001, 0, 0, 2, "MAP", "abc")), kNow, m));
    CHECK(r.counters().oversized_messages == 1);
    CHECK(r.bytes_held() == 0);
    CHECK_FALSE(r.add_fragment(1, parse(fragment(2, 65'000'000, 0, 0, 1000, "MAP", "abc")), kNow, m));  // the 65 MB claim
    CHECK(r.counters().oversized_messages == 2);
    const std::string half(50'000, 'h');
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 100'000, 0, 0, 2, "MAP", half)), kNow, m));
    REQUIRE(r.add_fragment(1, parse(fragment(3, 100'000, 50'000, 1, 2, "", half)), kNow, m));
    CHECK(m.payload.size() == 100'000);
    CHECK(r.bytes_held() == 0);
    // A message within the limit, sent in so many tiny fragments that their charge outgrows
    // the sender's share (max + 1/8): dropped, counted oversized.
    limits.max_message_bytes = 65536;
    LcmReassembler tiny(limits);
    bool refused = false;
    for (uint16_t k = 0; k < 5000 && !refused; ++k) {
        tiny.add_fragment(5, parse(fragment(1, 65536, k, k, 65535, k == 0 ? "T" : "", k == 0 ? "" : "x")), kNow, m);
        refused = tiny.counters().oversized_messages == 1;
        CHECK(tiny.bytes_held() <= limits.sender_limit());
    }
    CHECK(refused);
    CHECK(tiny.bytes_held() == 0);
}

TEST_CASE("lcm reassembly: an unfinished message expires after max_age_us, counted")
{
    ReassemblyLimits limits;
    limits.max_age_us = 1'000'000;
    LcmReassembler r(limits);
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(1, 6, 0, 0, 2, "A", "abc")), kNow, m));
    r.expire(kNow + 1'000'000);  // exactly the age: kept
    CHECK(r.counters().expired_messages == 0);
    // Its second fragment comes late: the message expired, the fragment begins a new one.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(1, 6, 3, 1, 2, "", "def")), kNow + 1'000'001, m));
    CHECK(r.counters().expired_messages == 1);
    CHECK(r.counters().incomplete_messages == 0);
    r.expire(kNow + 2'100'000);
    CHECK(r.counters().expired_messages == 2);
    CHECK(r.bytes_held() == 0);
    // A clock stepped back expires too, rather than keeping a message forever.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(2, 6, 0, 0, 2, "A", "abc")), kNow, m));
    r.expire(kNow - 5'000'000);
    CHECK(r.counters().expired_messages == 3);
    // Fragments within the age complete as ever.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 6, 0, 0, 2, "A", "abc")), kNow, m));
    REQUIRE(r.add_fragment(1, parse(fragment(3, 6, 3, 1, 2, "", "def")), kNow + 999'000, m));
    CHECK(text(m) == "abcdef");
}

TEST_CASE("lcm reassembly: at the memory bound the least recently used message is dropped, counted")
{
    ReassemblyLimits limits;
    limits.max_message_bytes = 100'000;
    limits.max_bytes_held = 170'000;
    LcmReassembler r(limits);
    LcmReassembler::Message m;
    const std::string chunk(60'000, 'c');
    CHECK_FALSE(r.add_fragment(1, parse(fragment(1, 100'000, 0, 0, 2, "A", chunk)), kNow, m));
    CHECK_FALSE(r.add_fragment(2, parse(fragment(1, 100'000, 0, 0, 2, "B", chunk)), kNow, m));
    CHECK(r.bytes_held() == 2 * (60'000 + kLcmFragmentHeaderBytes));
    // Sender 1 is the least recently used: C's fragment pushes it out.
    CHECK_FALSE(r.add_fragment(3, parse(fragment(1, 100'000, 0, 0, 2, "C", chunk)), kNow, m));
    CHECK(r.counters().evicted_messages == 1);
    CHECK(r.bytes_held() == 2 * (60'000 + kLcmFragmentHeaderBytes));
    CHECK(r.bytes_held() <= limits.bytes_held_limit());
    // B and C still complete (B's last fragment fits beside C); A's last fragment alone
    // begins a message that cannot complete.
    const std::string rest(40'000, 'r');
    REQUIRE(r.add_fragment(2, parse(fragment(1, 100'000, 60'000, 1, 2, "", rest)), kNow, m));
    CHECK(m.channel == "B");
    REQUIRE(r.add_fragment(3, parse(fragment(1, 100'000, 60'000, 1, 2, "", rest)), kNow, m));
    CHECK(m.channel == "C");
    CHECK(m.payload.size() == 100'000);
    CHECK(m.payload[59'999] == 'c');
    CHECK(m.payload[60'000] == 'r');
    CHECK_FALSE(r.add_fragment(1, parse(fragment(1, 100'000, 60'000, 1, 2, "", rest)), kNow, m));
    CHECK(r.counters().incomplete_messages == 0);
    CHECK(r.counters().evicted_messages == 1);
    CHECK(r.bytes_held() == 40'000 + kLcmFragmentHeaderBytes);
}
