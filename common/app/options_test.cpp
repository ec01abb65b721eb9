// --help names every built-in scene, from the same registry as the "unknown built-in scene" error: the two lists are
// the registry (builtin_scene_names()), name for name and in order, so a scene added to it shows up in both.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "../scene/builtin_scenes.h"
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

}  // namespace
}  // namespace rt
