"""The layout's limits (docs/architecture.md): no source file in solver/, engine/, app/ or gpu/
over 600 lines, no class with behaviour over 60 members, and the one-way dependencies (solver
and gpu include nothing of engine or app, engine nothing of app)."""
import pathlib
import re

import class_members

SOURCE = pathlib.Path(__file__).resolve().parents[2]
SUFFIXES = {".h", ".cpp", ".cu", ".cuh"}


def sources(folder):
    return [p for p in sorted((SOURCE / folder).rglob("*")) if p.suffix in SUFFIXES]


def test_no_source_file_is_over_600_lines():
    long = [f"{p.relative_to(SOURCE)}: {n} lines"
            for folder in ("solver", "engine", "app", "gpu") for p in sources(folder)
            if (n := len(p.read_text().splitlines())) > 600]
    assert not long, "\n".join(long)


# Plain data, whatever its few helpers: the frame's arrays, each a field the stages read.
PLAIN_DATA = {"FrameData"}


def test_no_class_with_behaviour_is_over_60_members():
    large = []
    for folder in ("solver", "engine", "app", "gpu"):
        for p in sources(folder):
            for name, data, functions in class_members.classes(p.read_text()):
                if functions > 0 and data + functions > 60 and name not in PLAIN_DATA:
                    large.append(f"{p.relative_to(SOURCE)}: {name} has {data} data members and "
                                 f"{functions} member functions")
    assert not large, "\n".join(large)


def test_the_member_count_reads_declarations_as_declared():
    code = """
    // class Commented { int a; };
    template <typename Exec>
    class A : public B<int, 2> {
     public:
      A(int x) : x_(x), v_{} {}
      int f() const { return x_ > 0 ? 1 : 2; }
      void g(int a, int b);
      template <typename T>
      void t(T v) { (void)v; }
      struct Inner { int p, q; void h(); };
      enum class E { One, Two };
      using T = int;
      friend class C;
      bool operator==(const A&) const = default;
      std::function<void(const A&)> callback;
     private:
      int x_ = 0, y_{1};
      std::vector<std::pair<int, int>> v_;
      static constexpr int kN = 3;
      RecentMedian m_{1u << 20}, n_{1u << 20};
      Inner inner_;
      std::optional<Clock::time_point> a_, b_, c_;
      char path_[1024] = {};
      const char* name_ = "a; b";
    };
    """
    counts = {name: (data, functions) for name, data, functions in class_members.classes(code)}
    assert counts == {"A": (13, 5), "Inner": (2, 1)}


def test_dependencies_point_one_way():
    forbidden = {"solver": ("engine/", "app/", "gpu/"), "gpu": ("engine/", "app/"),
                 "engine": ("app/",)}
    wrong = []
    for folder, layers in forbidden.items():
        for p in sources(folder):
            for included in re.findall(r'#include "([^"]+)"', p.read_text()):
                if included.startswith(layers):
                    wrong.append(f"{p.relative_to(SOURCE)} includes {included}")
    assert not wrong, "\n".join(wrong)
