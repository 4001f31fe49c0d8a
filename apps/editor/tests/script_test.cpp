// The editor's script language: every command parses, every mistake is reported with its line.
#include "script.hpp"

#include <gtest/gtest.h>

using namespace sylva::editor;

TEST(Script, ParsesEveryCommand) {
  const char* text = R"(# a comment
load "scenes/my meadow.json"
new
add_module grass
remove_module grass
set grass.field.density 120
set sun.elevation_deg=30   # trailing comment
brush op=raise radius=8 strength=0.5 falloff=smooth
stroke ground.height 10,20 30.5,-20 40,25
undo
undo 3
redo 2
camera 0 10 20
camera 0 10 20 45 -10 70
camera bookmark overview
bookmark home
frames 5
debug wireframe on
screenshot out/a.png 256x144
screenshot_ui out/ui.png
save
save out/scene.json
expect grass.field.density 120
expect_unsaved no
print done "with spaces"
load_default
export_tree "out/my trees"
quit
)";
  auto script = parse_script(text, "t.sylva");
  ASSERT_TRUE(script.ok()) << script.error().message;
  ASSERT_EQ(script->size(), 27u);
  const auto& c = *script;
  EXPECT_EQ(c[0].name, "load");
  EXPECT_EQ(c[0].line, 2);
  EXPECT_EQ(c[0].args[0], "scenes/my meadow.json");
  EXPECT_EQ(c[5].args, (std::vector<std::string>{"sun.elevation_deg", "30"}));
  EXPECT_EQ(c[7].name, "stroke");
  ASSERT_EQ(c[7].points.size(), 3u);
  EXPECT_EQ(c[7].points[1], glm::dvec2(30.5, -20));
  EXPECT_EQ(c[9].count, 3);
  EXPECT_EQ(c[10].count, 2);
  EXPECT_EQ(c[15].count, 5);
  EXPECT_EQ(c[23].args[1], "with spaces");
  EXPECT_EQ(c[24].name, "load_default");
  EXPECT_TRUE(c[24].args.empty());
  EXPECT_EQ(c[25].name, "export_tree");
  EXPECT_EQ(c[25].args, (std::vector<std::string>{"out/my trees"}));
  EXPECT_EQ(c.back().name, "quit");
  EXPECT_EQ(c.back().line, 28);
  auto missing = parse_script("export_tree\n", "t.sylva");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("export_tree FOLDER"), std::string::npos) << missing.error().message;
}

TEST(Script, ParsesTheFileCommands) {
  auto script = parse_script("copy_file a.lsys b.lsys\nwait_reload b.lsys\nwait_reload b.lsys 40\n"
                             "preview species=pillar derivations=4\npreview\nprint_stats voxel\n",
                             "t.sylva");
  ASSERT_TRUE(script.ok()) << script.error().message;
  ASSERT_EQ(script->size(), 6u);
  EXPECT_EQ((*script)[1].args, (std::vector<std::string>{"b.lsys"}));
  EXPECT_EQ((*script)[2].count, 40);
  EXPECT_EQ((*script)[3].args, (std::vector<std::string>{"species=pillar", "derivations=4"}));
  EXPECT_TRUE((*script)[4].args.empty());
}

TEST(Script, ParsesTheImportCommands) {
  auto script = parse_script("import_terrain dem.tif\nimport_terrain \"my dem.tif\" bake out.sylvaterrain hold\n"
                             "wait_import\nwait_import 500\ncancel_import\n",
                             "t.sylva");
  ASSERT_TRUE(script.ok()) << script.error().message;
  ASSERT_EQ(script->size(), 5u);
  EXPECT_EQ((*script)[1].args, (std::vector<std::string>{"my dem.tif", "bake", "out.sylvaterrain", "hold"}));
  EXPECT_EQ((*script)[3].count, 500);
  for (const char* bad : {"import_terrain", "import_terrain a.tif out.sylvaterrain", "import_terrain a.tif bake",
                          "import_terrain a.tif bake o.sylvaterrain later", "wait_import soon", "cancel_import now"}) {
    auto parsed = parse_script(bad, "t.sylva");
    ASSERT_FALSE(parsed.ok()) << bad;
    EXPECT_NE(parsed.error().message.find("t.sylva:1: "), std::string::npos) << parsed.error().message;
  }
}

TEST(Script, MistakesNameTheLine) {
  struct Case {
    const char* text;
    const char* must_mention;
  };
  const Case cases[] = {
      {"frobnicate", "t.sylva:1: unknown command \"frobnicate\""},
      {"new\n\nload", "t.sylva:3: load: expected load PATH"},
      {"stroke ground.height 10;20", "t.sylva:1: stroke: point 1"},
      {"stroke ground.height", "stroke: expected"},
      {"undo many", "t.sylva:1: undo: expected a whole number"},
      {"frames 0", "frames: expected a whole number in 1.."},
      {"camera 1 2", "camera: expected"},
      {"camera 1 2 x", "camera: expected a number, got \"x\""},
      {"camera bookmark", "camera bookmark NAME"},
      {"debug wireframe maybe", "debug: expected on or off"},
      {"screenshot a.png 10x10", "screenshot: size: 10x10 is outside 16..16384"},
      {"screenshot a.png 16384x16384", "above the limit"},
      {"brush radius", "brush: expected KEY=VALUE"},
      {"set onlypath", "set: expected set PATH VALUE"},
      {"set =3", "set: the parameter path before '=' is empty"},
      {"load \"unterminated", "t.sylva:1: unterminated quote"},
      {"expect_unsaved perhaps", "expect_unsaved: expected yes or no"},
      {"quit now", "quit: expected quit"},
      {"wait_reload", "wait_reload: expected wait_reload FILE [MAX_FRAMES]"},
      {"wait_reload a.lsys soon", "wait_reload: expected a whole number in 1.."},
      {"wait_reload a.lsys 0", "wait_reload: expected a whole number in 1.."},
      {"preview derivations", "preview: expected KEY=VALUE, got \"derivations\""},
      {"copy_file a.lsys", "copy_file: expected copy_file FROM TO"},
      {"print_stats", "print_stats: expected print_stats MODULE"},
  };
  for (const Case& c : cases) {
    auto script = parse_script(c.text, "t.sylva");
    ASSERT_FALSE(script.ok()) << c.text;
    EXPECT_NE(script.error().message.find(c.must_mention), std::string::npos)
        << "text: " << c.text << "\nmessage: " << script.error().message;
  }
  // A NUL byte would cut a path short when opened: the line is refused, not half-run.
  auto nul = parse_script(std::string("load a.json\0b\nquit\n", 19), "n.sylva");
  ASSERT_FALSE(nul.ok());
  EXPECT_NE(nul.error().message.find("n.sylva:1: the line holds a NUL byte"), std::string::npos) << nul.error().message;
  // Every bad line is reported, not only the first.
  auto many = parse_script("bogus1\nnew\nbogus2\n", "m.sylva");
  ASSERT_FALSE(many.ok());
  EXPECT_NE(many.error().message.find("m.sylva:1:"), std::string::npos);
  EXPECT_NE(many.error().message.find("m.sylva:3:"), std::string::npos);
}

TEST(Script, WordsPointsAndSizes) {
  EXPECT_EQ(split_words("  a \"b c\"\t\"d\\\"e\" # x").value(), (std::vector<std::string>{"a", "b c", "d\"e"}));
  EXPECT_TRUE(split_words("# only a comment").value().empty());
  EXPECT_EQ(parse_point("-1.5,2e3").value(), glm::dvec2(-1.5, 2000.0));
  EXPECT_FALSE(parse_point("1,").ok());
  EXPECT_FALSE(parse_point("nan,1").ok());
  EXPECT_EQ(parse_size("256x144").value(), glm::ivec2(256, 144));
  EXPECT_FALSE(parse_size("8x8").ok());
  EXPECT_TRUE(parse_script("", "empty").ok());
  EXPECT_TRUE(parse_script("\n\n# nothing\n", "empty").value().empty());
}
