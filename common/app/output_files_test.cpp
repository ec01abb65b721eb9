#include "output_files.h"

#include <climits>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "atomic_file.h"
#include "options.h"

namespace rt {
namespace {

namespace fs = std::filesystem;

// A fresh, empty folder per test.
fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(RT_TEST_OUTPUT_DIR) / "output_files" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

std::string read_text(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), {}};
}

std::size_t entries(const fs::path& dir) { return std::size_t(std::distance(fs::directory_iterator(dir), {})); }

std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

TEST(AtomicFile, TemporaryIsANewHiddenFileBesideTheTargetKeepingItsExtension) {
    const fs::path dir = scratch("temporary_name");
    const std::string a = create_temporary((dir / "w.png").string());
    const std::string b = create_temporary((dir / "w.png").string());
    EXPECT_NE(a, b);   // unique names: two writers never share a temporary
    for (const fs::path& p : {fs::path(a), fs::path(b)}) {
        EXPECT_EQ(p.parent_path(), dir);
        EXPECT_TRUE(p.filename().string().starts_with(".w.tmp-"));
        EXPECT_EQ(p.extension(), ".png");
        EXPECT_TRUE(fs::is_regular_file(p));
        EXPECT_EQ(fs::file_size(p), 0u);
    }
    discard_temporary(a);
    discard_temporary(b);
    EXPECT_EQ(entries(dir), 0u);
}

TEST(AtomicFile, TemporaryInAMissingFolderNamesTheUsersPath) {
    const fs::path target = scratch("missing_folder") / "no" / "w.png";
    EXPECT_EQ(message_of([&] { create_temporary(target.string()); }),
              "cannot write " + target.string() + ": No such file or directory");
}

TEST(AtomicFile, APathTooLongForItsTemporaryNamesTheUsersPath) {
    // Short enough itself, too long once the temporary's ".w.tmp-XXXXXXXXXX" is added beside it.
    const fs::path dir = scratch("long_path");
    std::string target = dir.string() + "/";
    while (target.size() < PATH_MAX - 12) target += "d/";
    target += "w.png";
    EXPECT_EQ(message_of([&] { create_temporary(target); }), "cannot write " + target + ": path too long");
}

TEST(RunOutputs, KeptOutputsStayAndNoTemporaryRemains) {
    const fs::path dir = scratch("kept");
    {
        RunOutputs files;
        files.reserve({"--stats", (dir / "s.json").string()});
        EXPECT_EQ(entries(dir), 1u);   // the temporary, created before rendering
        files.write({"--stats", (dir / "s.json").string()}, [](const std::string& f) { write_text(f, "{}"); });
        files.keep();
    }
    EXPECT_EQ(read_text(dir / "s.json"), "{}");
    EXPECT_EQ(entries(dir), 1u);
}

TEST(RunOutputs, AFailedRunRemovesEverythingItWrote) {
    const fs::path dir = scratch("failed");
    try {
        RunOutputs files;
        files.reserve({"--stats", (dir / "s.json").string()});
        files.write({"--out", (dir / "a_0000.png").string()}, [](const std::string& f) { write_text(f, "frame 0"); });
        EXPECT_TRUE(fs::exists(dir / "a_0000.png"));
        files.write({"--out", (dir / "a_0001.png").string()}, [](const std::string&) { throw std::runtime_error("disk full"); });
        FAIL() << "the failed write did not throw";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write --out " + (dir / "a_0001.png").string() + ": disk full");
    }
    EXPECT_EQ(entries(dir), 0u);   // the completed frame, the reserved temporary and the failed one are gone
}

TEST(RunOutputs, AFailedRenameNamesTheOptionAndLeavesNoTemporary) {
    // The target became a folder holding a file after the temporary was reserved: the rename fails (EISDIR).
    const fs::path dir = scratch("rename");
    RunOutputs files;
    const std::string target = (dir / "o.png").string();
    files.reserve({"--out", target});
    fs::create_directory(target);
    write_text(fs::path(target) / "inside", "x");
    const std::string message = message_of([&] {
        files.write({"--out", target}, [](const std::string& f) { write_text(f, "image"); });
    });
    EXPECT_TRUE(message.starts_with("cannot write --out " + target + ": ")) << message;
    EXPECT_EQ(entries(dir), 1u);   // the folder only: the temporary is gone
}

TEST(RunOutputs, WriterErrorsNameTheUsersPathNotTheTemporary) {
    const fs::path dir = scratch("error_names");
    RunOutputs files;
    const std::string target = (dir / "w.png").string();
    const std::string message = message_of([&] {
        files.write({"--out", target}, [](const std::string& f) { throw std::runtime_error("cannot open " + f + "\nline 2"); });
    });
    EXPECT_EQ(message, "cannot write --out " + target + ": cannot open " + target + " line 2");
}

TEST(CheckOutputs, AHardLinkToAnInputIsRefused) {
    const fs::path dir = scratch("hard_link");
    write_text(dir / "scene.gltf", "{}");
    fs::create_hard_link(dir / "scene.gltf", dir / "stats.json");
    const std::string message = message_of(
        [&] { check_outputs({{"--stats", (dir / "stats.json").string()}}, {(dir / "scene.gltf").string()}); });
    EXPECT_NE(message.find("is the scene's input file"), std::string::npos) << message;
    EXPECT_EQ(read_text(dir / "scene.gltf"), "{}");
}

TEST(CheckOutputs, TwoSpellingsOfOneNewFileAreTheSameOutput) {
    const fs::path dir = scratch("two_spellings");
    const std::string a = (dir / "x.png").string(), b = (dir / "." / ".." / dir.filename() / "x.png").string();
    EXPECT_EQ(message_of([&] { check_outputs({{"--out", a}, {"--stats", b}}, {}); }),
              "--stats " + b + ": is the same file as --out " + a);
    EXPECT_EQ(message_of([&] { check_outputs({{"--out", a}, {"--stats", (dir / "y.json").string()}}, {}); }), "");
}

TEST(NumberIn, RefusesNanAndInfWithOneReadableLine) {
    CLI::Validator v = number_in(1e-3, 1e4);
    std::string text = "nan";
    EXPECT_EQ(v(text), "nan is not a finite number");
    text = "-inf";
    EXPECT_EQ(v(text), "-inf is not a finite number");
    text = "1e999";   // overflows to infinity
    EXPECT_EQ(v(text), "1e999 is not a finite number");
    text = "0";
    EXPECT_EQ(v(text), "0 is out of range: must be at least 0.001 and at most 10000");
    text = "24";
    EXPECT_EQ(v(text), "");
    CLI::Validator positive = number_in(0, 1e6, true);
    text = "0";
    EXPECT_EQ(positive(text), "0 is out of range: must be above 0 and at most 1000000");
}

}  // namespace
}  // namespace rt
