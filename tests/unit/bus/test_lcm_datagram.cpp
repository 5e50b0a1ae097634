// LCM's udpm datagrams decoded from hand-made bytes, and fragment reassembly.
#include <catch2/catch.hpp>

#include <string>
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
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 6, 2, 3, "", "ghi")), m));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 0, 0, 3, "MAP", "abc")), m));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 0, 0, 3, "MAP", "abc")), m));  // again
    REQUIRE(r.add_fragment(1, parse(fragment(4, 9, 3, 1, 3, "", "def")), m));
    CHECK(m.channel == "MAP");
    CHECK(text(m) == "abcdefghi");
    CHECK(r.counters().incomplete_messages == 0);
    CHECK(r.counters().invalid_datagrams == 0);
    // A late duplicate of a finished message starts a new one, which never completes.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(4, 9, 3, 1, 3, "", "def")), m));
}

TEST_CASE("lcm reassembly: a new message from a sender abandons its unfinished one, and it is counted")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(7, parse(fragment(1, 6, 0, 0, 2, "A", "abc")), m));
    // Fragment 1 of message 1 was lost; message 2 begins.
    CHECK_FALSE(r.add_fragment(7, parse(fragment(2, 6, 0, 0, 2, "A", "ABC")), m));
    CHECK(r.counters().incomplete_messages == 1);
    REQUIRE(r.add_fragment(7, parse(fragment(2, 6, 3, 1, 2, "", "DEF")), m));
    CHECK(text(m) == "ABCDEF");
}

TEST_CASE("lcm reassembly: two senders interleaved are kept apart")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(5, 4, 0, 0, 2, "ONE", "ab")), m));
    CHECK_FALSE(r.add_fragment(2, parse(fragment(5, 4, 0, 0, 2, "TWO", "AB")), m));
    REQUIRE(r.add_fragment(2, parse(fragment(5, 4, 2, 1, 2, "", "CD")), m));
    CHECK(m.channel == "TWO");
    CHECK(text(m) == "ABCD");
    REQUIRE(r.add_fragment(1, parse(fragment(5, 4, 2, 1, 2, "", "cd")), m));
    CHECK(m.channel == "ONE");
    CHECK(text(m) == "abcd");
    CHECK(r.counters().incomplete_messages == 0);
}

TEST_CASE("lcm reassembly: fragments that contradict their message or do not tile it are invalid")
{
    LcmReassembler r;
    LcmReassembler::Message m;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 6, 0, 0, 2, "A", "abc")), m));
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 8, 3, 1, 2, "", "def")), m));  // another size
    CHECK(r.counters().invalid_datagrams == 1);
    // All fragments there, but only 5 of the 6 bytes: not handed out.
    CHECK_FALSE(r.add_fragment(1, parse(fragment(3, 6, 3, 1, 2, "", "de")), m));
    CHECK(r.counters().invalid_datagrams == 2);
    // Not LCM at all.
    const std::vector<uint8_t> junk{1, 2, 3, 4, 5, 6, 7, 8, 9};
    CHECK_FALSE(r.add_fragment(1, parse(junk), m));
    CHECK(r.counters().invalid_datagrams == 3);
}

TEST_CASE("lcm reassembly: datagrams claiming big messages cannot make it hold more than its budget")
{
    // Three senders each begin a 40 MiB message (as garbage could, 20 bytes each): the third
    // pushes the total past 96 MiB, so the least recently used unfinished one is dropped.
    LcmReassembler r;
    LcmReassembler::Message m;
    const uint32_t big = 40u << 20;
    CHECK_FALSE(r.add_fragment(1, parse(fragment(1, big, 0, 0, 1000, "A", "x")), m));
    CHECK_FALSE(r.add_fragment(2, parse(fragment(1, big, 0, 0, 1000, "B", "x")), m));
    CHECK(r.bytes_in_progress() == 2 * std::size_t{big});
    CHECK_FALSE(r.add_fragment(3, parse(fragment(1, big, 0, 0, 1000, "C", "x")), m));
    CHECK(r.bytes_in_progress() == 2 * std::size_t{big});
    CHECK(r.counters().incomplete_messages == 1);
    // A small message still goes through, and finishing it frees its bytes.
    CHECK_FALSE(r.add_fragment(4, parse(fragment(1, 4, 0, 0, 2, "D", "ab")), m));
    REQUIRE(r.add_fragment(4, parse(fragment(1, 4, 2, 1, 2, "", "cd")), m));
    CHECK(text(m) == "abcd");
    CHECK(r.bytes_in_progress() == 2 * std::size_t{big});
}
