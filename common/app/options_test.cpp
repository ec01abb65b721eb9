// --help names every built-in scene, from the same registry as the "unknown built-in scene" error: the two lists are
// the registry (builtin_scene_names()), name for name and in order, so a scene added to it shows up in both.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "common/scene/builtin/builtin_scenes.h"
#include "driver.h"
#include "options.h"

namespace rt {
namespace {

// "a, b, c; spheres takes a count, spheres:N" -> {a, b, c}: the names before the ';'.
std::vector<std::string> names_in(const std::string& list) {
    std::vector<std::string> names;
    std::istringstream in(list.substr(0, list.find(';')));
    std::string name;
    while (std::getline(in, name, ',')) names.push_back(name.substr(name.find_first_not_of(' ')));
    return names;
}

// The text between `open` and the first `close` after it, or "" when `open` is not in `text`.
std::string between(const std::string& text, const std::string& open, const std::string& close) {
    const std::size_t start = text.find(open);
    if (start == std::string::npos) return "";
    const std::size_t from = start + open.size();
    return text.substr(from, text.find(close, from) - from);
}

std::string help_text() {
    CLI::App app("test");
    Options options;
    add_shared_options(app, options);
    return app.help();
}

TEST(SharedOptions, HelpListsEveryBuiltinScene) {
    const std::string help = help_text();
    const std::string scene_line = between(help, "--scene", "\n  --");   // the option and its description
    ASSERT_FALSE(scene_line.empty()) << help;
    for (const std::string& name : builtin_scene_names()) {
        EXPECT_NE(scene_line.find(name), std::string::npos) << "--help does not name builtin:" << name << ":\n" << help;
    }
    EXPECT_EQ(names_in(between(scene_line, "builtin:NAME (", ")")), builtin_scene_names()) << scene_line;
    EXPECT_NE(scene_line.find("spheres:N"), std::string::npos) << scene_line;
}

TEST(SharedOptions, HelpAndUnknownSceneErrorGiveTheSameList) {
    std::string error;
    try {
        make_builtin_scene("teapot");
    } catch (const SceneError& e) {
        error = e.what();
    }
    ASSERT_FALSE(error.empty()) << "builtin:teapot was accepted";
    const std::string error_list = between(error, "(known: ", ")");
    const std::string help_list = between(between(help_text(), "--scene", "\n  --"), "builtin:NAME (", ")");
    EXPECT_EQ(error_list, builtin_scene_list()) << error;
    EXPECT_EQ(help_list, error_list);
    EXPECT_EQ(names_in(error_list), builtin_scene_names()) << error;
}

// What a validator makes of `text`: "" when it accepts (then `text` is what CLI11 reads), else its reason.
std::string check(const CLI::Validator& v, std::string& text) { return v(text); }

TEST(NumberValidators, IntegerOptionsRefuseEverythingButDecimalWholeNumbersAndSayWhy) {
    const CLI::Validator v = whole_number_in(0, 32);
    for (const std::string bad : {"", " ", " 4", "4 ", "4.0", "1e1", "0x10", "nan", "inf", "4-", "--4", "+", "-1", "33",
                                  "99999999999999999999"}) {
        std::string text = bad;
        EXPECT_NE(check(v, text), "") << "'" << bad << "' was accepted";
    }
    std::string text = "-0";
    EXPECT_EQ(check(v, text), "");
    EXPECT_EQ(text, "0");
    text = "08";   // CLI11 alone reads a leading 0 as octal (and refuses 08)
    EXPECT_EQ(check(v, text), "");
    EXPECT_EQ(text, "8");
    text = "+32";
    EXPECT_EQ(check(v, text), "");
    EXPECT_EQ(text, "32");
    text = "4.0";
    EXPECT_EQ(check(v, text), "'4.0' is not a whole number");
    text = "";
    EXPECT_EQ(check(v, text), "the value is empty (expected a number)");
}

TEST(NumberValidators, AnIntegerSetRefusesTheEmptyStringInsteadOfReadingItAsZero) {
    const CLI::Validator v = whole_number_of({4, 8, 16});
    for (const std::string bad : {"", " ", "0", "5", "4.0", "0x10", " 8"}) {
        std::string text = bad;
        EXPECT_NE(check(v, text), "") << "'" << bad << "' was accepted";
    }
    std::string text = "5";
    EXPECT_EQ(check(v, text), "5 is not one of 4, 8 or 16");
    text = "016";
    EXPECT_EQ(check(v, text), "");
    EXPECT_EQ(text, "16");
}

TEST(NumberValidators, FloatOptionsRefuseBlanksHexAndNonFiniteValuesAndPassOnAnExactSpelling) {
    const CLI::Validator v = number_in(0, 1e6, true);
    for (const std::string bad : {"", " ", " 1", "1 ", "0x10", "0X1p3", "nan", "inf", "1e400", "-1e400", "0", "-0", "x"}) {
        std::string text = bad;
        EXPECT_NE(check(v, text), "") << "'" << bad << "' was accepted";
    }
    std::string text = "0.1";
    EXPECT_EQ(check(v, text), "");
    EXPECT_EQ(std::stod(text), 0.1);   // the same double, whatever the spelling
    text = "4.0";
    EXPECT_EQ(check(v, text), "");
    EXPECT_EQ(text, "4");
}

// One rule for extension case: every output option takes its format's extension in any case.
TEST(SharedOptions, OutputExtensionsAreTakenInAnyCase) {
    for (const char* name : {"x.GLB", "x.Gltf", "x.glb"}) {
        Options o;
        o.export_path = name;
        EXPECT_NO_THROW(validate_options(o)) << name;
    }
    for (const char* name : {"o.PNG", "o.Png"}) {
        Options o;
        o.out = name;
        o.heatmap = std::string("h_") + name;
        EXPECT_NO_THROW(validate_options(o)) << name;
    }
    Options o;
    o.export_path = "x.GLBX";
    EXPECT_THROW(validate_options(o), std::invalid_argument);
}

TEST(ErrorLines, ControlCharactersInAMessageAreEscapedSoItStaysOneLine) {
    EXPECT_EQ(one_printable_line("cannot read scene a\nb.gltf"), "cannot read scene a\\nb.gltf");
    EXPECT_EQ(one_printable_line(std::string("x\ty\rz\x01\x7f")), "x\\ty\\rz\\x01\\x7f");
    EXPECT_EQ(one_printable_line("caf\xc3\xa9.gltf"), "caf\xc3\xa9.gltf");   // UTF-8 stays as it is
}

}  // namespace
}  // namespace rt
