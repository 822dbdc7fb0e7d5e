// Argument parsing of the motionfx subcommands.
#include "apps/cli.h"

#include <gtest/gtest.h>

namespace mfx::cli {
namespace {

const std::vector<OptionSpec> kOptions = {
    {"out", "DIR", "output"}, {"size", "WxH", "size"}, {"validate", "", "flag"}};

Result<ParsedArgs> parse(std::vector<std::string> words, size_t maxPositional = 1) {
    return parseArgs(words, kOptions, maxPositional);
}

TEST(CliParsing, ValuesFlagsAndPositionals) {
    auto r = parse({"scene.json", "--out", "frames", "--size=64x32", "--validate"});
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r.value().value("out"), "frames");
    EXPECT_EQ(r.value().value("size"), "64x32");
    EXPECT_TRUE(r.value().has("validate"));
    EXPECT_EQ(r.value().positional, std::vector<std::string>{"scene.json"});
}

TEST(CliParsing, Rejections) {
    EXPECT_FALSE(parse({"--nope"}).ok());
    EXPECT_FALSE(parse({"--out"}).ok());
    EXPECT_FALSE(parse({"--out="}).ok());
    EXPECT_FALSE(parse({"--validate=yes"}).ok());
    EXPECT_FALSE(parse({"--out", "a", "--out", "b"}).ok());
    EXPECT_FALSE(parse({"a", "b"}).ok());
    EXPECT_FALSE(parse({"-o"}).ok());
}

TEST(CliParsing, ErrorNamesTheOption) {
    auto r = parse({"--colour", "red"});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("--colour"), std::string::npos);
}

TEST(CliParsing, HelpIsAlwaysAccepted) {
    auto r = parse({"--help"});
    ASSERT_TRUE(r.ok());
    EXPECT_TRUE(r.value().has("help"));
}

TEST(CliParsing, Sizes) {
    auto ok = parseSize("1280x720", 16384);
    ASSERT_TRUE(ok.ok());
    EXPECT_EQ(ok.value().first, 1280u);
    EXPECT_EQ(ok.value().second, 720u);
    for (const char* bad : {"", "x", "12x", "x12", "0x5", "5x0", "-1x5", "12x12x", "1.5x2",
                            "20000x10", " 12x12", "12x12 "})
        EXPECT_FALSE(parseSize(bad, 16384).ok()) << "'" << bad << "'";
}

} // namespace
} // namespace mfx::cli
