"""Imports run one way: no cycle among the project's modules (the course's four, pyrt/,
course_kit/, benchmarks/), counting the imports inside functions too, so that each module
can be read, tested and shipped with only what lies beneath it (docs/maintaining.md)."""
import ast

from helpers import REPO

PACKAGES = ("pyrt", "course_kit", "benchmarks")


def project_modules():
    """{dotted name: path} of every module of the project (tests and course data aside)."""
    modules = {path.stem: path for path in REPO.glob("*.py")}
    for package in PACKAGES:
        for path in (REPO / package).rglob("*.py"):
            parts = path.relative_to(REPO).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            modules[".".join(parts)] = path
    return modules


def imported_names(path, name):
    """The dotted names that the module `name` at path imports, anywhere in it; a relative
    import is made absolute."""
    package = name if path.stem == "__init__" else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(parent + ([base] if base else []))
            yield base
            # `from package import module` imports the module
            yield from (f"{base}.{alias.name}" for alias in node.names)


def import_graph(modules):
    """{module: set of the project's modules it imports}. Importing a.b.c loads the
    packages a and a.b too: they count."""
    graph = {}
    for name, path in modules.items():
        found = set()
        for imported in imported_names(path, name):
            parts = imported.split(".")
            found.update(".".join(parts[:end]) for end in range(1, len(parts) + 1))
        graph[name] = {module for module in found if module in modules and module != name}
    return graph


def find_cycle(graph):
    """A list of modules [a, b, ..., a] that import each other round, or None."""
    state = {}  # module: "open" while its imports are being followed, then "done"

    def visit(module, path):
        state[module] = "open"
        for imported in sorted(graph[module]):
            if state.get(imported) == "open":
                return path[path.index(imported):] + [imported]
            if imported not in state:
                cycle = visit(imported, path + [imported])
                if cycle:
                    return cycle
        state[module] = "done"
        return None

    for module in sorted(graph):
        if module not in state:
            cycle = visit(module, [module])
            if cycle:
                return cycle
    return None


def test_no_import_cycle_among_the_projects_modules():
    cycle = find_cycle(import_graph(project_modules()))
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_the_cycle_finder_names_a_cycle_and_sees_none_where_there_is_none():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set()}) is None


def test_the_graph_counts_imports_inside_functions_and_of_packages(tmp_path):
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "__init__.py").write_text("")
    (tmp_path / "pkg" / "low.py").write_text("def f():\n    import top\n")
    (tmp_path / "pkg" / "mid.py").write_text("from . import low\n")
    (tmp_path / "top.py").write_text("from pkg.mid import thing\n")
    modules = {"pkg": tmp_path / "pkg" / "__init__.py", "pkg.low": tmp_path / "pkg" / "low.py",
               "pkg.mid": tmp_path / "pkg" / "mid.py", "top": tmp_path / "top.py"}
    graph = import_graph(modules)
    assert graph == {"pkg": set(), "pkg.low": {"top"}, "pkg.mid": {"pkg", "pkg.low"},
                     "top": {"pkg", "pkg.mid"}}
    assert find_cycle(graph) == ["pkg.low", "top", "pkg.mid", "pkg.low"]


def test_the_graph_sees_the_course_modules_on_top_of_pyrt():
    graph = import_graph(project_modules())
    assert "pyrt.rendering" in graph["PyRT_Integrators"]
    assert "PyRT_Core" in graph["pyrt.scalar_intersections"]
    assert not any(module.startswith("course_kit") for name, imported in graph.items()
                   if not name.startswith(("course_kit", "benchmarks"))
                   for module in imported)
