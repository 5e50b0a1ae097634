#include <catch2/catch.hpp>

#include "frame_helpers.hpp"
#include "ugv/canopen/sdo.hpp"

using namespace ugv::canopen;
using canopen_test::frame;
using canopen_test::text;

TEST_CASE("Expedited download requests: the fact sheet vector and every size")
{
    // 602#2B40600006000000 writes controlword 0x0006 to node 2.
    CHECK(text(encode_sdo_download(2, {0x6040, 0}, 0x0006, 2)) == "602#2B40600006000000");
    CHECK(text(encode_sdo_download(2, {0x607A, 0}, 0x12345678, 4)) == "602#237A600078563412");
    CHECK(text(encode_sdo_download(2, {0x1A00, 1}, 0x00ABCDEF, 3)) == "602#27001A01EFCDAB00");
    CHECK(text(encode_sdo_download(2, {0x6060, 0}, 0x01, 1)) == "602#2F60600001000000");
    CHECK(text(encode_sdo_upload(2, {0x6041, 0})) == "602#4041600000000000");
}

TEST_CASE("Requests decode on the server side")
{
    auto r = decode_sdo_request(frame("602#2B40600006000000"), 2);
    REQUIRE(r);
    CHECK(r->kind == SdoRequest::Kind::download);
    CHECK(r->at == SdoAddress{0x6040, 0});
    CHECK(r->size == 2);
    CHECK(r->value == 6);
    r = decode_sdo_request(frame("602#4064600000000000"), 2);
    REQUIRE(r);
    CHECK(r->kind == SdoRequest::Kind::upload);
    CHECK(r->at == SdoAddress{0x6064, 0});
    CHECK_FALSE(decode_sdo_request(frame("603#4064600000000000"), 2));
    // Segmented download initiate (not expedited) is reported as unsupported.
    r = decode_sdo_request(frame("602#2108100004000000"), 2);
    REQUIRE(r);
    CHECK(r->kind == SdoRequest::Kind::unsupported);
}

TEST_CASE("Responses: write ack, 4/3/2/1-byte reads, abort")
{
    CHECK(text(encode_sdo_download_ack(2, {0x6040, 0})) == "582#6040600000000000");
    CHECK(text(encode_sdo_upload_reply(2, {0x6041, 0}, 0x0237, 2)) == "582#4B41600037020000");
    CHECK(text(encode_sdo_abort(0x582, {0x2000, 0}, abort_code::no_object)) == "582#8000200000000206");

    auto r = decode_sdo_response(frame("582#4364600078563412"), 2);
    REQUIRE(r);
    CHECK(r->kind == SdoResponse::Kind::upload_data);
    CHECK(r->size == 4);
    CHECK(r->value == 0x12345678u);
    r = decode_sdo_response(frame("582#47646000785634FF"), 2);
    CHECK(r->size == 3);
    CHECK(r->value == 0x345678u);
    r = decode_sdo_response(frame("582#4B646000785634FF"), 2);
    CHECK(r->size == 2);
    CHECK(r->value == 0x5678u);
    r = decode_sdo_response(frame("582#4F616000015634FF"), 2);
    CHECK(r->size == 1);
    CHECK(r->value == 0x01u);
    r = decode_sdo_response(frame("582#8000200000000206"), 2);
    CHECK(r->kind == SdoResponse::Kind::abort);
    CHECK(r->value == 0x06020000u);
    CHECK(r->at == SdoAddress{0x2000, 0});
    CHECK(describe_abort(0x06020000) == "0x06020000 object does not exist");
    CHECK(describe_abort(0x06090030) == "0x06090030 value range of parameter exceeded");
}

TEST_CASE("SDO client: one transfer at a time, results through callbacks")
{
    SdoClient client(2, 100'000);
    std::vector<ugv::io::CanFrame> out;
    std::vector<std::string> log;
    client.write({0x6040, 0}, 6, 2, [&](const SdoResult& r) { log.push_back(r.ok ? "write ok" : "write fail"); });
    client.read({0x6041, 0}, [&](const SdoResult& r) { log.push_back(r.ok ? "read " + std::to_string(r.value) : "read fail"); });
    client.tick(0, out);
    REQUIRE(out.size() == 1);
    CHECK(text(out[0]) == "602#2B40600006000000");
    out.clear();
    client.tick(50'000, out);
    CHECK(out.empty());  // the read waits for the write's answer
    // A reply for another object is not taken for this one.
    CHECK(client.on_frame(frame("582#6041600000000000"), 50'000, out));
    CHECK(log.empty());
    CHECK(client.on_frame(frame("582#6040600000000000"), 60'000, out));
    REQUIRE(log == std::vector<std::string>{"write ok"});
    REQUIRE(out.size() == 1);  // the next one goes out at once
    CHECK(text(out[0]) == "602#4041600000000000");
    out.clear();
    CHECK(client.on_frame(frame("582#4B41600037020000"), 70'000, out));
    CHECK(log.back() == "read 567");
    CHECK(client.idle());
    CHECK_FALSE(client.on_frame(frame("702#05"), 80'000, out));
}

TEST_CASE("SDO client: a timeout is retried, then fails with abort code 0x05040000")
{
    SdoClient client(2, 100'000, 1);
    std::vector<ugv::io::CanFrame> out;
    std::optional<SdoResult> result;
    client.read({0x6064, 0}, [&](const SdoResult& r) { result = r; });
    client.tick(0, out);
    client.tick(100'000, out);
    CHECK(out.size() == 1);
    client.tick(100'001, out);  // retry
    REQUIRE(out.size() == 2);
    CHECK(out[1] == out[0]);
    client.tick(200'002, out);  // gives up: abort to the server
    REQUIRE(out.size() == 3);
    CHECK(text(out[2]) == "602#8064600000000405");
    REQUIRE(result);
    CHECK_FALSE(result->ok);
    CHECK(result->timed_out);
    CHECK(result->abort_code == abort_code::timeout);
    CHECK(client.timeouts() == 2);
    CHECK(client.idle());
}

TEST_CASE("SDO client: an abort fails the transfer with the server's code")
{
    SdoClient client(2, 100'000);
    std::vector<ugv::io::CanFrame> out;
    std::optional<SdoResult> result;
    client.write({0x1A00, 1}, 0x60640020, 4, [&](const SdoResult& r) { result = r; });
    client.tick(0, out);
    client.on_frame(frame("582#80001A0141000406"), 1000, out);
    REQUIRE(result);
    CHECK_FALSE(result->ok);
    CHECK_FALSE(result->timed_out);
    CHECK(result->abort_code == abort_code::not_mappable);
    CHECK(client.aborts() == 1);
}
