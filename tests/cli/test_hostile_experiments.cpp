// Experiment files written as a hostile user would: every case is refused when the file is read, with exit
// 2 and one line naming file:line: table.key, and every file around it (a previous result set in the output
// folder, the folder above it) is left byte for byte as it was. Then plot texts that would be gnuplot code
// (backticks, `!cmd` after a newline, system()) run nothing and reach the plot script as literal text.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// A valid experiment the cases extend: one axis, two tiny configurations.
const std::string kBase = R"([experiment]
name = "hostile"
[scene.camera]
size = 32
[[sweep]]
key = "light.incidence"
values = [0, 30]
)";

/// The same without the tables a case redefines.
const std::string kNoExperiment = "[scene.camera]\nsize = 32\n[[sweep]]\nkey = \"light.incidence\"\nvalues = [0, 30]\n";
const std::string kNoSweep = "[experiment]\nname = \"hostile\"\n[scene.camera]\nsize = 32\n";

struct Case {
    const char* what;
    std::string text;  ///< the whole file; the line the message must name ends in "# <-"
    const char* key;   ///< what the message names after file:line: ("" for a TOML syntax error)
};

std::string base(const std::string& more) { return kBase + more; }
/// `first` before the tables of `rest` (a top-level key after a table header would belong to that table).
std::string top(const std::string& first, const std::string& rest = kBase) { return first + rest; }

const std::vector<Case>& cases() {
    static const std::vector<Case> all = {
        // -- top-level shapes
        {"plot = [1, 2] (segfaulted)", top("plot = [1, 2] # <-\n"), "plot"},
        {"plot = a number", top("plot = 3 # <-\n"), "plot"},
        {"[plot] as a single table", base("[plot] # <-\nfile = \"a.png\"\n"), "plot"},
        {"plot = [{...}, 1]", top("plot = [{ file = \"a.png\" }, 1] # <-\n"), "plot"},
        {"[sweep] as a single table", kNoSweep + "[sweep] # <-\nkey = \"light.incidence\"\nvalues = [0]\n", "sweep"},
        {"sweep = a string", top("sweep = \"light.incidence\" # <-\n", kNoSweep), "sweep"},
        {"sweep = [1]", top("sweep = [1] # <-\n", kNoSweep), "sweep"},
        {"strip = a string", top("strip = \"copper\" # <-\n"), "strip"},
        {"[strip] as a single table", base("[strip] # <-\nmaterial = \"copper\"\n"), "strip"},
        {"pareto = 1", top("pareto = 1 # <-\n"), "pareto"},
        {"[pareto] as a single table", base("[pareto] # <-\nfile = \"p.png\"\n"), "pareto"},
        {"experiment = 1", top("experiment = 1 # <-\n", kNoExperiment), "experiment"},
        {"[[experiment]]", kNoExperiment + "[[experiment]] # <-\nname = \"x\"\n", "experiment"},
        {"scene = 1", "scene = 1 # <-\n[[sweep]]\nkey = \"light.incidence\"\nvalues = [0]\n", "scene"},
        {"match = [1]", top("match = [1] # <-\n"), "match"},
        {"summary = \"x\"", top("summary = \"x\" # <-\n"), "summary"},
        {"contact_sheet = 1", top("contact_sheet = 1 # <-\n"), "contact_sheet"},
        {"reference = true", top("reference = true # <-\n"), "reference"},
        {"timing = 3", top("timing = 3 # <-\n"), "timing"},
        {"[plots] (did you mean plot)", base("[plots] # <-\nfile = \"a.png\"\n"), "plots"},
        {"[sumary]", base("[sumary] # <-\nseries = \"model\"\n"), "sumary"},
        {"a stray top-level key", top("foo = 1 # <-\n"), "foo"},
        // -- [experiment]
        {"name = 1", kNoExperiment + "[experiment]\nname = 1 # <-\n", "experiment.name"},
        {"name = ../x", kNoExperiment + "[experiment]\nname = \"../x\" # <-\n", "experiment.name"},
        {"name = a/b", kNoExperiment + "[experiment]\nname = \"a/b\" # <-\n", "experiment.name"},
        {"name = empty", kNoExperiment + "[experiment]\nname = \"\" # <-\n", "experiment.name"},
        {"name = ..", kNoExperiment + "[experiment]\nname = \"..\" # <-\n", "experiment.name"},
        {"name = /abs", kNoExperiment + "[experiment]\nname = \"/tmp/hilite-abs\" # <-\n", "experiment.name"},
        {"name with a newline", kNoExperiment + "[experiment]\nname = \"a\\nb\" # <-\n", "experiment.name"},
        {"name with a tab", kNoExperiment + "[experiment]\nname = \"a\\tb\" # <-\n", "experiment.name"},
        {"name = .hidden", kNoExperiment + "[experiment]\nname = \".hidden\" # <-\n", "experiment.name"},
        {"name = -rf", kNoExperiment + "[experiment]\nname = \"-rf\" # <-\n", "experiment.name"},
        {"name of 300 bytes", kNoExperiment + "[experiment]\nname = \"" + std::string(300, 'a') + "\" # <-\n",
         "experiment.name"},
        {"title = 3", kNoExperiment + "[experiment]\ntitle = 3 # <-\n", "experiment.title"},
        {"description = []", kNoExperiment + "[experiment]\ndescription = [] # <-\n", "experiment.description"},
        {"nmae (did you mean name)", kNoExperiment + "[experiment]\nnmae = \"x\" # <-\n", "experiment.nmae"},
        // -- [scene]
        {"scene key misspelt", base("[scene.material]\nroughnes = 0.1 # <-\n"), "material.roughnes"},
        {"scene table misspelt", base("[scene.materail] # <-\nroughness = 0.1\n"), "materail"},
        {"scene roughness a word", base("[scene.material]\nroughness = \"abc\" # <-\n"), "material.roughness"},
        {"scene roughness negative", base("[scene.material]\nroughness = -1 # <-\n"), "material.roughness"},
        {"scene model unknown", base("[scene.material]\nmodel = \"gggx\" # <-\n"), "material.model"},
        {"scene key in the wrong table", base("[scene.light]\nroughness = 0.1 # <-\n"), "light.roughness"},
        {"incidence list per configuration (found after rows before)",
         kNoSweep +
             "[scene.light]\nincidence = \"0:30:10\" # <-\n[[sweep]]\nkey = \"material.model\"\nvalues = [\"ggx\"]\n",
         "light.incidence"},
        {"incidence list as an array per configuration",
         kNoSweep +
             "[scene.light]\nincidence = [0, 30] # <-\n[[sweep]]\nkey = \"material.model\"\nvalues = [\"ggx\"]\n",
         "light.incidence"},
        {"incidence range as a sweep value",
         kNoSweep + "[[sweep]]\nkey = \"light.incidence\"\nvalues = [\"0:30:10\"] # <-\n", "light.incidence"},
        // -- [[sweep]]
        {"values and range",
         base("[[sweep]]\nkey = \"material.roughness\"\nvalues = [0.1] # <-\nrange = [0, 1, 0.5]\n"), "sweep.values"},
        {"values and cases", base("[[sweep]]\nkey = \"s\"\nvalues = [0.1] # <-\ncases = [{ name = \"a\" }]\n"),
         "sweep.values"},
        {"neither values nor range", base("[[sweep]]\nkey = \"material.roughness\" # <-\n"), "sweep.key"},
        {"valuse (did you mean values)", base("[[sweep]]\nkey = \"material.roughness\"\nvaluse = [0.1] # <-\n"),
         "sweep.valuse"},
        {"no key", base("[[sweep]] # <-\nvalues = [0.1]\n"), "sweep.key"},
        {"key = 5", base("[[sweep]]\nkey = 5 # <-\nvalues = [0.1]\n"), "sweep.key"},
        {"key = empty", base("[[sweep]]\nkey = \"\" # <-\nvalues = [0.1]\n"), "sweep.key"},
        {"key without a table", base("[[sweep]]\nkey = \"roughness\"\nvalues = [0.1] # <-\n"), "roughness"},
        {"key misspelt", base("[[sweep]]\nkey = \"material.roughnes\"\nvalues = [0.1] # <-\n"), "material.roughnes"},
        {"key in an unknown table", base("[[sweep]]\nkey = \"materail.roughness\"\nvalues = [0.1] # <-\n"),
         "materail.roughness"},
        {"values = 3", base("[[sweep]]\nkey = \"material.roughness\"\nvalues = 3 # <-\n"), "sweep.values"},
        {"values = []", base("[[sweep]]\nkey = \"material.roughness\"\nvalues = [] # <-\n"), "sweep.values"},
        {"values = [a table]", base("[[sweep]]\nkey = \"material.roughness\"\nvalues = [{ a = 1 }] # <-\n"),
         "material.roughness"},
        {"values = [a word]", base("[[sweep]]\nkey = \"material.roughness\"\nvalues = [0.1, \"x\"] # <-\n"),
         "material.roughness"},
        {"values = [-1]", base("[[sweep]]\nkey = \"material.roughness\"\nvalues = [-1] # <-\n"), "material.roughness"},
        {"values = [nan]", base("[[sweep]]\nkey = \"material.roughness\"\nvalues = [nan] # <-\n"),
         "material.roughness"},
        {"model misspelt in values", base("[[sweep]]\nkey = \"material.model\"\nvalues = [\"gggx\"] # <-\n"),
         "material.model"},
        {"an empty param list", base("[[sweep]]\nkey = \"material.param\"\nvalues = [[]] # <-\n"), "material.param"},
        {"range of two", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [0, 1] # <-\n"), "sweep.range"},
        {"range backwards", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [1, 0, 0.1] # <-\n"), "sweep.range"},
        {"range step 0", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [0, 1, 0] # <-\n"), "sweep.range"},
        {"range step negative", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [0, 1, -1] # <-\n"),
         "sweep.range"},
        {"range of words", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [\"a\", 1, 2] # <-\n"),
         "sweep.range"},
        {"range to nan", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [0, nan, 1] # <-\n"), "sweep.range"},
        {"range to inf", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [0, inf, 1] # <-\n"), "sweep.range"},
        {"range of 1e18 values", base("[[sweep]]\nkey = \"material.roughness\"\nrange = [0, 1e12, 1e-6] # <-\n"),
         "sweep.range"},
        {"range = a string", base("[[sweep]]\nkey = \"material.roughness\"\nrange = \"0:1:0.1\" # <-\n"),
         "sweep.range"},
        {"cases = []", base("[[sweep]]\nkey = \"s\"\ncases = [] # <-\n"), "sweep.cases"},
        {"cases = [1]", base("[[sweep]]\nkey = \"s\"\ncases = [1] # <-\n"), "sweep.cases"},
        {"a case without a name", base("[[sweep]]\nkey = \"s\"\ncases = [{ material = { roughness = 0.1 } }] # <-\n"),
         "sweep.cases.name"},
        {"a case name = 3", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = 3 }] # <-\n"), "sweep.cases.name"},
        {"two cases named alike", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\" }, { name = \"a\" }] # <-\n"),
         "sweep.cases.name"},
        {"case tags = 3", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", tags = 3 }] # <-\n"),
         "sweep.cases.tags"},
        {"case reference = 3", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", reference = 3 }] # <-\n"),
         "sweep.cases.reference"},
        {"case with a stray key", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", colour = 1 }] # <-\n"),
         "sweep.cases.colour"},
        {"case scene key misspelt",
         base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", material = { roughnes = 0.1 } }] # <-\n"),
         "material.roughnes"},
        {"case tag an array", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", tags = { k = [1] } }] # <-\n"),
         "sweep.cases.tags.k"},
        {"case tag inf", base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", tags = { k = inf } }] # <-\n"),
         "sweep.cases.tags.k"},
        {"case tag named config",
         base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", tags = { config = 1 } }] # <-\n"),
         "sweep.cases.tags.config"},
        {"case reference table unknown",
         base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", reference = { lights = 1 } }] # <-\n"),
         "sweep.cases.reference.lights"},
        {"case axis named config", base("[[sweep]]\nkey = \"config\" # <-\ncases = [{ name = \"a\" }]\n"), "sweep.key"},
        {"case axis named like a parameter", base("[[sweep]]\nkey = \"roughness\" # <-\ncases = [{ name = \"a\" }]\n"),
         "sweep.key"},
        {"case tag named like a measurement",
         base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", tags = { aspect = 1 } }] # <-\n"), "sweep.cases"},
        {"case tag named like the axis",
         base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", tags = { s = 1 } }] # <-\n"), "sweep.cases.tags.s"},
        {"case roughness a word",
         base("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", material = { roughness = \"x\" } }] # <-\n"),
         "material.roughness"},
        // -- [[plot]]
        {"plot fiel (did you mean file)", base("[[plot]]\nfiel = \"a.png\" # <-\n"), "plot.fiel"},
        {"plot file ../x.png", base("[[plot]]\nfile = \"../x.png\" # <-\n"), "plot.file"},
        {"plot file absolute", base("[[plot]]\nfile = \"/tmp/hilite-x.png\" # <-\n"), "plot.file"},
        {"plot file in a subfolder", base("[[plot]]\nfile = \"a/b.png\" # <-\n"), "plot.file"},
        {"plot file empty", base("[[plot]]\nfile = \"\" # <-\n"), "plot.file"},
        {"plot file .txt", base("[[plot]]\nfile = \"x.txt\" # <-\n"), "plot.file"},
        {"plot file results.csv", base("[[plot]]\nfile = \"results.csv\" # <-\n"), "plot.file"},
        {"plot file results.jsonl", base("[[plot]]\nfile = \"results.jsonl\" # <-\n"), "plot.file"},
        {"plot file summary.md", base("[[plot]]\nfile = \"summary.md\" # <-\n"), "plot.file"},
        {"plot file experiment.toml", base("[[plot]]\nfile = \"experiment.toml\" # <-\n"), "plot.file"},
        {"plot file .png", base("[[plot]]\nfile = \".png\" # <-\n"), "plot.file"},
        {"plot file with a control character", base("[[plot]]\nfile = \"a\\u0001.png\" # <-\n"), "plot.file"},
        {"plot file with a newline", base("[[plot]]\nfile = \"a\\n.png\" # <-\n"), "plot.file"},
        {"plot file = 3", base("[[plot]]\nfile = 3 # <-\n"), "plot.file"},
        {"plot file only .png", base("[[plot]]\nfile = \"png\" # <-\n"), "plot.file"},
        {"two plots named alike", base("[[plot]]\nfile = \"a.png\"\n[[plot]]\nfile = \"a.png\" # <-\n"), "plot.file"},
        {"two plots by default name", base("[[plot]]\ny = \"aspect\"\n[[plot]] # <-\ny = \"eccentricity\"\n"),
         "plot.file"},
        {"plot and pareto named alike",
         base("[[sweep]]\nkey = \"setting\"\ncases = [{ name = \"a\", tags = { knob = \"k\" } "
              "}]\n[timing]\n[[plot]]\nfile = \"x.png\"\n"
              "[[pareto]]\nfile = \"x.png\" # <-\n"),
         "pareto.file"},
        {"plot named like a strip's Fresnel plot",
         base("[[plot]]\nfile = \"copper_fresnel.png\"\n[[strip]]\nmaterial = \"copper\" # <-\n"), "strip.material"},
        {"plot named like the contact sheet",
         base("[[plot]]\nfile = \"sheet.png\"\n[contact_sheet]\nfile = \"sheet.png\" # <-\nrows = [\"ggx\"]\ncolumns = "
              "[0]\n"),
         "contact_sheet.file"},
        {"plot x not a row field", base("[[plot]]\nx = \"incidence_degs\" # <-\n"), "plot.x"},
        {"plot y = 3", base("[[plot]]\ny = 3 # <-\n"), "plot.y"},
        {"plot y not a row field", base("[[plot]]\ny = \"aspekt\" # <-\n"), "plot.y"},
        {"plot series not a row field", base("[[plot]]\nseries = \"nope\" # <-\n"), "plot.series"},
        {"plot x a table", base("[[plot]]\n[plot.x] # <-\na = 1\n"), "plot.x"},
        {"plot key with a command", base("[[plot]]\nkey = \"top left\\n!touch /tmp/hilite-key\" # <-\n"), "plot.key"},
        {"plot key system()", base("[[plot]]\nkey = \"top left; system('touch /tmp/hilite-key')\" # <-\n"), "plot.key"},
        {"plot key not a position", base("[[plot]]\nkey = \"bottom\" # <-\n"), "plot.key"},
        {"plot key = 1", base("[[plot]]\nkey = 1 # <-\n"), "plot.key"},
        {"plot logx = yes", base("[[plot]]\nlogx = \"yes\" # <-\n"), "plot.logx"},
        {"plot logy = 1", base("[[plot]]\nlogy = 1 # <-\n"), "plot.logy"},
        {"plot title = [1]", base("[[plot]]\ntitle = [1] # <-\n"), "plot.title"},
        {"plot xlabel = 1", base("[[plot]]\nxlabel = 1 # <-\n"), "plot.xlabel"},
        {"plot ylabel = true", base("[[plot]]\nylabel = true # <-\n"), "plot.ylabel"},
        {"theory a string", base("[[plot]]\ntheory = \"cos(x)\" # <-\n"), "plot.theory"},
        {"theory one string", base("[[plot]]\ntheory = [[\"a\"]] # <-\n"), "plot.theory"},
        {"theory expression a number", base("[[plot]]\ntheory = [[\"a\", 1]] # <-\n"), "plot.theory"},
        {"theory system()", base("[[plot]]\ntheory = [[\"a\", \"system(\\\"touch /tmp/hilite-th\\\")\"]] # <-\n"),
         "plot.theory"},
        {"theory backticks", base("[[plot]]\ntheory = [[\"a\", \"`touch /tmp/hilite-th`\"]] # <-\n"), "plot.theory"},
        {"theory newline then !cmd", base("[[plot]]\ntheory = [[\"a\", \"1\\n!touch /tmp/hilite-th\"]] # <-\n"),
         "plot.theory"},
        {"theory then a plot command", base("[[plot]]\ntheory = [[\"a\", \"1 with lines, '/etc/passwd'\"]] # <-\n"),
         "plot.theory"},
        {"theory unknown variable", base("[[plot]]\ntheory = [[\"a\", \"y*2\"]] # <-\n"), "plot.theory"},
        {"theory assignment", base("[[plot]]\ntheory = [[\"a\", \"x=1\"]] # <-\n"), "plot.theory"},
        {"theory a list", base("[[plot]]\ntheory = [[\"a\", \"1,2\"]] # <-\n"), "plot.theory"},
        {"theory empty", base("[[plot]]\ntheory = [[\"a\", \"\"]] # <-\n"), "plot.theory"},
        {"theory unbalanced", base("[[plot]]\ntheory = [[\"a\", \"cos(x\"]] # <-\n"), "plot.theory"},
        {"theory gnuplot's ** power", base("[[plot]]\ntheory = [[\"a\", \"x**2\"]] # <-\n"), "plot.theory"},
        {"theory a string literal", base("[[plot]]\ntheory = [[\"a\", \"\\\"abc\\\"\"]] # <-\n"), "plot.theory"},
        // -- [contact_sheet]
        {"sheet without rows", base("[contact_sheet] # <-\ncolumns = [0]\n"), "contact_sheet.rows"},
        {"sheet without columns", base("[contact_sheet] # <-\nrows = [\"ggx\"]\n"), "contact_sheet.columns"},
        {"sheet rows = []", base("[contact_sheet]\nrows = [] # <-\ncolumns = [0]\n"), "contact_sheet.rows"},
        {"sheet fov 0", base("[contact_sheet]\nrows = [\"ggx\"]\ncolumns = [0]\nfov = 0 # <-\n"), "contact_sheet.fov"},
        {"sheet fov a word", base("[contact_sheet]\nrows = [\"ggx\"]\ncolumns = [0]\nfov = \"wide\" # <-\n"),
         "contact_sheet.fov"},
        {"sheet fov a table", base("[contact_sheet]\nrows = [\"ggx\"]\ncolumns = [0]\nfov = { a = 1 } # <-\n"),
         "contact_sheet.fov"},
        {"sheet rows a string", base("[contact_sheet]\nrows = \"ggx\" # <-\ncolumns = [0]\n"), "contact_sheet.rows"},
        {"sheet row_key misspelt",
         base("[contact_sheet]\nrow_key = \"material.modle\"\nrows = [\"ggx\"] # <-\ncolumns = [0]\n"),
         "material.modle"},
        {"sheet row value unknown (found after rows before)",
         base("[contact_sheet]\nrows = [\"gggx\"] # <-\ncolumns = [0]\n"), "material.model"},
        {"sheet column value out of range", base("[contact_sheet]\nrows = [\"ggx\"]\ncolumns = [0, 95] # <-\n"),
         "light.incidence"},
        {"sheet column a range", base("[contact_sheet]\nrows = [\"ggx\"]\ncolumns = [\"0:30:10\"] # <-\n"),
         "light.incidence"},
        {"sheet size a word", base("[contact_sheet]\nsize = \"huge\" # <-\nrows = [\"ggx\"]\ncolumns = [0]\n"),
         "contact_sheet.size"},
        {"sheet size 0", base("[contact_sheet]\nsize = \"0\" # <-\nrows = [\"ggx\"]\ncolumns = [0]\n"),
         "contact_sheet.size"},
        {"sheet size = [3]", base("[contact_sheet]\nsize = [3] # <-\nrows = [\"ggx\"]\ncolumns = [0]\n"),
         "contact_sheet.size"},
        {"sheet file outside", base("[contact_sheet]\nfile = \"../sheet.png\" # <-\nrows = [\"ggx\"]\ncolumns = [0]\n"),
         "contact_sheet.file"},
        {"sheet fiel", base("[contact_sheet]\nfiel = \"s.png\" # <-\nrows = [\"ggx\"]\ncolumns = [0]\n"),
         "contact_sheet.fiel"},
        {"sheet of 65 rows",
         base("[contact_sheet]\nrow_key = \"material.roughness\"\nrows = [" +
              [] {
                  std::string v;
                  for (int i = 0; i < 65; ++i) v += (i ? ", " : "") + std::to_string(0.01 * (i + 1));
                  return v;
              }() +
              "] # <-\ncolumns = [0]\n"),
         "contact_sheet.rows"},
        {"sheet row_key = 1", base("[contact_sheet]\nrow_key = 1 # <-\nrows = [\"ggx\"]\ncolumns = [0]\n"),
         "contact_sheet.row_key"},
        // -- [[strip]]
        {"strip without material", base("[[strip]] # <-\nfile = \"s.png\"\n"), "strip.material"},
        {"strip material unknown", base("[[strip]]\nmaterial = \"unobtainium\" # <-\n"), "strip.material"},
        {"strip material = 1", base("[[strip]]\nmaterial = 1 # <-\n"), "strip.material"},
        {"strip file outside", base("[[strip]]\nmaterial = \"copper\"\nfile = \"../s.png\" # <-\n"), "strip.file"},
        {"strip colour", base("[[strip]]\nmaterial = \"copper\"\ncolour = \"red\" # <-\n"), "strip.colour"},
        {"two strips of one material",
         base("[[strip]]\nmaterial = \"copper\"\n[[strip]] # <-\nmaterial = \"copper\"\n"), "strip.file"},
        // -- [summary]
        {"summary serie", base("[summary]\nserie = \"model\" # <-\n"), "summary.serie"},
        {"summary series = 1", base("[summary]\nseries = 1 # <-\n"), "summary.series"},
        {"summary series not a row field", base("[summary]\nseries = \"nope\" # <-\n"), "summary.series"},
        {"summary x not a row field", base("[summary]\nx = \"nope\" # <-\n"), "summary.x"},
        {"summary at a string", base("[summary]\nat = \"0\" # <-\n"), "summary.at"},
        {"summary at words", base("[summary]\nat = [\"a\"] # <-\n"), "summary.at"},
        {"summary at nan", base("[summary]\nat = [nan] # <-\n"), "summary.at"},
        {"summary sections unknown", base("[summary]\nsections = [\"shapes\"] # <-\n"), "summary.sections"},
        {"summary sections a string", base("[summary]\nsections = \"shape\" # <-\n"), "summary.sections"},
        // -- [reference], [timing], [[pareto]], [match]
        {"reference errors = yes", base("[reference]\nerrors = \"yes\" # <-\n"), "reference.errors"},
        {"reference error (did you mean errors)", base("[reference]\nerror = true # <-\n"), "reference.error"},
        {"timing repeats 0", base("[timing]\nrepeats = 0 # <-\n"), "timing.repeats"},
        {"timing repeats 1.5", base("[timing]\nrepeats = 1.5 # <-\n"), "timing.repeats"},
        {"timing warmup -1", base("[timing]\nwarmup = -1 # <-\n"), "timing.warmup"},
        {"timing repats", base("[timing]\nrepats = 3 # <-\n"), "timing.repats"},
        {"pareto fil", base("[[pareto]]\nfil = \"x.png\" # <-\n"), "pareto.fil"},
        {"pareto file outside", base("[[pareto]]\nfile = \"../p.png\" # <-\n"), "pareto.file"},
        {"pareto targets words", base("[[pareto]]\ntargets = [\"a\"] # <-\n"), "pareto.targets"},
        {"pareto targets inf", base("[[pareto]]\ntargets = [inf] # <-\n"), "pareto.targets"},
        {"pareto setting not a row field (no case axis)", base("[[pareto]] # <-\n"), "pareto.setting"},
        {"pareto error not a row field",
         base("[[sweep]]\nkey = \"setting\"\ncases = [{ name = \"a\", tags = { knob = \"k\" } }]\n"
              "[timing]\n[[pareto]]\nerror = \"aspect_eror\" # <-\n"),
         "pareto.error"},
        {"pareto time without [timing]",
         base("[[sweep]]\nkey = \"setting\"\ncases = [{ name = \"a\", tags = { knob = \"k\" } }]\n"
              "[[pareto]]\nerror = \"aspect\"\ntime = \"time_ms\" # <-\n"),
         "pareto.time"},
        {"match table misspelt", base("[match]\n[match.materail] # <-\nmodel = \"ggx\"\n"), "materail"},
        {"match material = 1", base("[match]\nmaterial = 1 # <-\n"), "material"},
        // -- TOML itself
        {"unclosed table header", base("[[plot] # <-\n"), ""},
        {"a table defined twice", base("[experiment] # <-\nname = \"again\"\n"), ""},
        {"a key given twice", base("[[plot]]\nfile = \"a.png\"\nfile = \"b.png\" # <-\n"), ""},
        {"invalid UTF-8", base("[[plot]]\ntitle = \"\xff\xfe\" # <-\n"), ""},
    };
    return all;
}

/// Every file under `root` with its bytes (folders as "<dir>"), to compare before and after.
std::map<std::string, std::string> snapshot(const fs::path& root) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        const std::string rel = fs::relative(e.path(), root).string();
        if (e.is_directory()) {
            out[rel] = "<dir>";
            continue;
        }
        std::ifstream in(e.path(), std::ios::binary);
        std::ostringstream ss;
        ss << in.rdbuf();
        out[rel] = ss.str();
    }
    return out;
}

/// The 1-based line of `text` ending in the marker "# <-" (0 if none).
int markedLine(const std::string& text) {
    std::istringstream in(text);
    int n = 0;
    for (std::string l; std::getline(in, l);) {
        ++n;
        if (l.size() >= 4 && l.compare(l.size() - 4, 4, "# <-") == 0) return n;
    }
    return 0;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

TEST_CASE("cli::run hostile experiment files: exit 2, one line naming file:line: key, every file as it was") {
    REQUIRE(cases().size() >= 100);
    hilite_test::TempDir d("hilite-hostile");
    // A previous result set in the output folder, which no refused run may touch.
    fs::create_directories(d.path / "out");
    for (const char* f : {"results.csv", "results.jsonl", "experiment.toml", "summary.md", "plot.png", "plot.dat",
                          "plot.gp", "contact_sheet.png", "a.png", "x.png"})
        d.write(std::string("out/") + f, std::string("previous ") + f + "\n");
    const std::string file = d / "case.toml";
    for (const Case& c : cases()) {
        const std::string what = c.what;
        CAPTURE(what);
        CAPTURE(c.text);
        d.write("case.toml", c.text);
        const auto before = snapshot(d.path);
        const auto r = hilite_test::hilite("run " + file + " -o " + (d / "out"));
        CAPTURE(r.out);
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        const int line = markedLine(c.text);
        REQUIRE(line > 0);
        const std::string where = "hilite: " + file + ":" + std::to_string(line) + ": ";
        CHECK(r.out.rfind(where, 0) == 0);
        if (*c.key) CHECK(r.out.compare(where.size(), std::string(c.key).size() + 2, std::string(c.key) + ": ") == 0);
        else CHECK(r.out.find("TOML syntax error") != std::string::npos);
        CHECK(r.out.find("internal error") == std::string::npos);
        CHECK(snapshot(d.path) == before);
        for (const char* outside : {"/tmp/hilite-abs", "/tmp/hilite-x.png", "/tmp/hilite-key", "/tmp/hilite-th"})
            CHECK_FALSE(fs::exists(outside));
    }
}

// The errors that were found only after every row was measured (a contact-sheet value, a plot field, an
// incidence list) against a real result set: a plain run and a --resume into it leave it as it was.
TEST_CASE("cli::run late errors are found before a real previous result set is touched") {
    hilite_test::TempDir d("hilite-hostile-real");
    const std::string good = d.write("good.toml", base("[[plot]]\nfile = \"aspect.png\"\n"));
    REQUIRE(hilite_test::hilite("run " + good + " -o " + (d / "out")).code == 0);
    REQUIRE(fs::exists(d / "out/results.jsonl"));
    for (const char* late :
         {"[contact_sheet]\nrows = [\"gggx\"]\ncolumns = [0]\n", "[[plot]]\nfile = \"b.png\"\ny = \"aspekt\"\n",
          "[contact_sheet]\nsize = \"0\"\nrows = [\"ggx\"]\ncolumns = [0]\n",
          "[scene.light]\nincidence = \"0:30:10\"\n[[sweep]]\nkey = \"material.model\"\nvalues = [\"ggx\"]\n"}) {
        CAPTURE(late);
        const std::string text = std::string(late).find("[scene.light]") == 0 ? kNoSweep + late : base(late);
        const std::string bad = d.write("bad.toml", text);
        const auto before = snapshot(d.path);
        for (const char* resume : {"", " --resume"}) {
            const auto r = hilite_test::hilite("run " + bad + " -o " + (d / "out") + resume);
            CAPTURE(r.out);
            CHECK(r.code == 2);
            CHECK(hilite_test::lines(r.out) == 1);
            CHECK(r.out.rfind("hilite: " + bad + ":", 0) == 0);
            CHECK(snapshot(d.path) == before);
        }
    }
}

TEST_CASE("cli::run unknown keys name the closest allowed one and list them all") {
    hilite_test::TempDir d("hilite-hostile-hint");
    const auto r =
        hilite_test::hilite("run " + d.write("e.toml", base("[[plot]]\nfiel = \"a.png\"\n")) + " -o " + (d / "o"));
    CHECK(r.code == 2);
    CHECK(r.out.find("plot.fiel: unknown key, did you mean 'file'? (allowed: file, title, x, y, series") !=
          std::string::npos);
    const auto s = hilite_test::hilite(
        "run " + d.write("s.toml", kNoSweep + "[sweep]\nkey = \"light.incidence\"\nvalues = [0]\n") + " -o " +
        (d / "o"));
    CHECK(s.out.find("sweep: write it as [[sweep]] tables") != std::string::npos);
    const auto k =
        hilite_test::hilite("run " + d.write("k.toml", base("[[plot]]\nkey = \"bottom\"\n")) + " -o " + (d / "o"));
    CHECK(k.out.find("(allowed: top left, top center, top right") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "o"));
}

// Texts that gnuplot would run if they were pasted into its script as code, or into a double-quoted
// string: a backtick command, a newline then `!cmd`, system(). Each one's marker file must not appear.
TEST_CASE("cli::run plot titles, labels, series and theory titles are data: nothing runs, the text reaches the plot") {
    hilite_test::TempDir d("hilite-inject");
    const std::string mark = (d / "pwned");
    const std::string tick = "`touch " + mark + "1`", bang = "\\n!touch " + mark + "2\\n",
                      sys = "system(\\\"touch " + mark + "3\\\")", quote = "it''s";
    const std::string text =
        "[experiment]\nname = \"inject\"\n[scene.camera]\nsize = 32\n"
        "[[sweep]]\nkey = \"series\"\ncases = [{ name = \"A " +
        tick +
        "\", material = { model = \"ggx\" } },"
        " { name = \"B " +
        bang +
        "\", material = { model = \"phong\" } }]\n"
        "[[sweep]]\nkey = \"light.incidence\"\nvalues = [0, 60]\n"
        "[[plot]]\nfile = \"aspect.png\"\nseries = \"series\"\n"
        "title = \"T " +
        tick + " " + sys + " it's\"\nxlabel = \"X " + bang + "\"\nylabel = \"Y " + sys +
        "\"\n"
        "key = \"top right\"\n"
        "theory = [[\"cos " +
        tick + bang + sys + "\", \"cos(x*pi/180)\"], [\"half\", \"0.5\"]]\n";
    const auto r = hilite_test::hilite("run " + d.write("inject.toml", text) + " -o " + (d / "out"));
    CAPTURE(r.out);
    REQUIRE(r.code == 0);
    for (int i = 1; i <= 3; ++i) CHECK_FALSE(fs::exists(mark + std::to_string(i)));
    CHECK(fs::exists(d / "out/aspect.png"));
    const std::string gp = slurp(d / "out/aspect.gp");
    CAPTURE(gp);
    // Every text is one single-quoted gnuplot string (a quote doubled, a newline a space), on its own line.
    const std::string t = "`touch " + mark + "1`", s = "system(\"touch " + mark + "3\")", b = " !touch " + mark + "2 ";
    CHECK(gp.find("set title 'T " + t + " " + s + " " + quote + "'\n") != std::string::npos);
    CHECK(gp.find("set xlabel 'X " + b + "'\n") != std::string::npos);
    CHECK(gp.find("set ylabel 'Y " + s + "'\n") != std::string::npos);
    CHECK(gp.find("title 'A " + t + "'") != std::string::npos);
    CHECK(gp.find("title 'B " + b + "'") != std::string::npos);
    CHECK(gp.find("title 'cos " + t + b + s + "'") != std::string::npos);
    CHECK(gp.find("set key top right box opaque\n") != std::string::npos);
    CHECK(gp.find("cos(") == std::string::npos);  // the theory is data, not a gnuplot expression
    CHECK(gp.find('"') == gp.find("\"touch"));    // no double-quoted gnuplot string anywhere but inside the texts
    // No line of the script starts with '!' (a shell command) and each line is one command.
    std::istringstream lines(gp);
    for (std::string l; std::getline(lines, l);) CHECK((l.empty() || l[0] != '!'));
    // The theory curves as data: cos(x) at the rows' x values and between them, no NaN anywhere.
    const std::string dat = slurp(d / "out/aspect.dat");
    const auto at = dat.find("# theory: cos ");
    REQUIRE(at != std::string::npos);
    std::istringstream block(dat.substr(dat.find('\n', at) + 1));
    int points = 0;
    for (std::string l; std::getline(block, l) && !l.empty();) {
        double x = 0, y = 0;
        std::istringstream(l) >> x >> y;
        CHECK(y == doctest::Approx(std::cos(x * M_PI / 180)).epsilon(1e-12));
        ++points;
    }
    CHECK(points >= 201);
    CHECK(dat.find("nan") == std::string::npos);
    CHECK(dat.find("inf") == std::string::npos);
    CHECK(dat.find("# theory: half\n0 0.5\n") != std::string::npos);
}
