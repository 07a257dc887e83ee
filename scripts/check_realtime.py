#!/usr/bin/env python3
"""The real-time contract, checked (J7): a function marked HAPTICCTRL_RT (base/realtime.hpp) calls
only marked functions of the project, and nothing outside it that allocates, locks, throws or does
I/O.

Reads the AST of the core's translation units (the rooms in ROOMS, with the flags of the build's
compile_commands.json) through libclang. For every marked function's body it follows each call:
- to a function of the project: the callee (or the template it instantiates) must be marked;
- outside the project (the standard library, Eigen, libc): its qualified name must not match
  FORBIDDEN (allocation, locks and waits, threads, stdio and files, sockets, strings and growing
  containers); a dynamic-size Eigen object must not be made;
- `new`, `delete` and `throw` expressions are refused outright.
An override of a marked virtual function must be marked too (a call through the base reaches it).
Calls through a function pointer are not followed (the core makes none in a cycle); a lambda's
body is checked as part of the function it is written in.

usage: check_realtime.py [--build DIR] [SOURCE_DIR]   exit 1 naming each violation
       check_realtime.py --self-test                   plants one violation of each kind in a
                                                       scratch file and fails unless each is found
"""
import ctypes
import json
import os
import re
import shlex
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor

try:
    import clang.cindex as ci
except ImportError:  # a Python of its own (pyenv) does not see Debian's python3-clang-14
    sys.path.append('/usr/lib/python3/dist-packages')
    import clang.cindex as ci

MARK = 'hapticctrl::rt'
# The rooms whose code runs in the core's cycle (docs/architecture.md, *The real-time contract*).
ROOMS = ('rt_core/src/', 'shm/src/')
FUNCTIONS = {ci.CursorKind.FUNCTION_DECL, ci.CursorKind.CXX_METHOD, ci.CursorKind.CONSTRUCTOR,
             ci.CursorKind.DESTRUCTOR, ci.CursorKind.CONVERSION_FUNCTION,
             ci.CursorKind.FUNCTION_TEMPLATE}
# Outside the project: what allocates, blocks, throws or does I/O, by qualified name.
FORBIDDEN = re.compile(
    r'^(?:operator new|operator delete|malloc|calloc|realloc|free|strdup|'
    r'(?:f|s|sn|v|vf|vs|vsn)?printf|puts|fputs|fwrite|fread|fopen|fclose|fflush|'
    r'open|openat|close|read|write|pread|pwrite|send|sendto|recv|recvfrom|poll|select|'
    r'usleep|sleep|nanosleep|pthread_mutex_lock|pthread_join|pthread_create|abort|exit|'
    r'std::(?:__\w+::)?(?:'
    r'(?:basic_)?string::(?!(?:data|size|length|empty|c_str|begin|end|operator\[\])$)\S+|'
    r'to_string|getline|stoi|stod|'
    r'(?:vector|deque|list|map|set|unordered_map|unordered_set|multimap)::'
    r'(?:push_back|emplace_back|push_front|emplace|insert|resize|reserve|assign|operator=|'
    r'(?:vector|deque|list|map|set|unordered_map|unordered_set|multimap))|'
    r'function::function|function::operator=|'
    r'make_shared|make_unique|allocate_shared|shared_ptr::shared_ptr|unique_ptr::unique_ptr|'
    r'(?:recursive_|timed_|shared_)?mutex::(?:lock|lock_shared)|'
    r'lock_guard::lock_guard|unique_lock::unique_lock|scoped_lock::scoped_lock|'
    r'shared_lock::shared_lock|condition_variable(?:_any)?::wait\w*|'
    r'thread::thread|thread::join|jthread::\w+|this_thread::sleep_\w+|'
    r'(?:basic_)?(?:o|i|io)?(?:f|string)?stream::\w+|operator<<|operator>>|'
    r'stable_sort|inplace_merge|stable_partition|format|vformat|'
    r'__throw_\w+|rethrow_exception|throw_with_nested))$')


def qualified_name(cursor):
    parts = []
    c = cursor
    while c is not None and c.kind != ci.CursorKind.TRANSLATION_UNIT:
        if c.kind in (ci.CursorKind.NAMESPACE, ci.CursorKind.CLASS_DECL, ci.CursorKind.STRUCT_DECL,
                      ci.CursorKind.CLASS_TEMPLATE,
                      ci.CursorKind.CLASS_TEMPLATE_PARTIAL_SPECIALIZATION) or c.kind in FUNCTIONS:
            if c.spelling:
                parts.append(c.spelling)
        c = c.semantic_parent
    return '::'.join(reversed(parts))


def in_project(cursor, root):
    f = cursor.location.file
    if f is None:
        return False
    path = os.path.realpath(f.name)
    return path.startswith(root + os.sep) and not path.startswith(os.path.join(root, 'build'))


def is_marked(cursor):
    return any(c.kind == ci.CursorKind.ANNOTATE_ATTR and c.spelling == MARK
               for c in cursor.get_children())


def template_of(cursor):
    t = ci.conf.lib.clang_getSpecializedCursorTemplate(cursor)
    return None if t is None or t.kind.is_invalid() else t


def overridden(cursor):
    """The functions `cursor` overrides (clang_getOverriddenCursors, not wrapped by cindex)."""
    lib = ci.conf.lib
    out = ctypes.POINTER(ci.Cursor)()
    n = ctypes.c_uint(0)
    lib.clang_getOverriddenCursors.argtypes = [ci.Cursor, ctypes.POINTER(ctypes.POINTER(ci.Cursor)),
                                               ctypes.POINTER(ctypes.c_uint)]
    lib.clang_getOverriddenCursors(cursor, ctypes.byref(out), ctypes.byref(n))
    usrs, names = [], []
    for i in range(n.value):  # read before the array is freed
        base = out[i]
        base._tu = cursor._tu  # pylint: disable=protected-access
        usrs.append(base.get_usr())
        names.append(qualified_name(base))
    lib.clang_disposeOverriddenCursors(out)
    return list(zip(usrs, names))


def where(cursor, root):
    loc = cursor.location
    name = os.path.relpath(loc.file.name, root) if loc.file else '?'
    return f'{name}:{loc.line}'


def arguments(entry):
    args = entry['arguments'] if 'arguments' in entry else shlex.split(entry['command'])
    kept = []
    skip = False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a in ('-o', '-c', '-MF', '-MT', '-MQ'):
            skip = a != '-c'
            continue
        if a == entry['file'] or a.endswith(os.path.basename(entry['file'])) or a.startswith(
                ('-fsanitize', '-W', '-fno-sanitize', '-fstack-clash', '-fcf-protection')):
            continue
        kept.append(a)
    return kept + ['-Wno-everything']


def read_unit(job):
    """Parses one translation unit: (marked USRs, facts about marked bodies and overrides)."""
    path, args, root = job
    tu = ci.Index.create().parse(path, args=args)
    errors = [d for d in tu.diagnostics if d.severity >= ci.Diagnostic.Error]
    if errors:
        return set(), [], [], [f'{path}: libclang could not parse it: {errors[0].spelling}']
    marked, bodies, overrides = set(), [], []
    seen = set()

    def visit(cursor):
        for c in cursor.get_children():
            if not in_project(c, root):
                continue
            if c.kind in FUNCTIONS:
                usr, at, marked_here = c.get_usr(), where(c, root), is_marked(c)
                if marked_here:
                    marked.add(usr)
                if c.kind == ci.CursorKind.CXX_METHOD and c.is_virtual_method():
                    for base_usr, base_name in overridden(c):
                        overrides.append((usr, base_usr, qualified_name(c), base_name, at))
                if c.is_definition() and (usr, at) not in seen:
                    seen.add((usr, at))
                    bodies.append((usr, marked_here, qualified_name(c), at, calls_in(c, root)))
            visit(c)

    visit(tu.cursor)
    return marked, bodies, overrides, []


def calls_in(function, root):
    """Every call, new, delete and throw in a function's body (lambdas' bodies included)."""
    found = []

    def walk(cursor):
        for c in cursor.get_children():
            k = c.kind
            if k == ci.CursorKind.CXX_NEW_EXPR:
                found.append(('new', where(c, root), None, None, None))
            elif k == ci.CursorKind.CXX_DELETE_EXPR:
                found.append(('delete', where(c, root), None, None, None))
            elif k == ci.CursorKind.CXX_THROW_EXPR:
                found.append(('throw', where(c, root), None, None, None))
            elif k == ci.CursorKind.CALL_EXPR and c.referenced is not None:
                callee = c.referenced
                template = template_of(callee)
                lambda_call = (callee.spelling == 'operator()' and callee.semantic_parent is not None
                               and callee.semantic_parent.spelling == '')
                # A compiler-made (implicit or `= default`) constructor, assignment or destructor
                # does what its members' do; the cycle's structs hold fixed-size members only.
                made_by_compiler = callee.is_default_method() or (
                    callee.kind in (ci.CursorKind.CONSTRUCTOR, ci.CursorKind.DESTRUCTOR)
                    and callee.extent.start == callee.semantic_parent.extent.start)
                if not lambda_call and not made_by_compiler:
                    ours = in_project(callee, root)
                    found.append(('call', where(c, root), callee.get_usr(),
                                  template.get_usr() if template else None,
                                  (qualified_name(callee), ours, where(callee, root) if ours else '',
                                   c.type.spelling if callee.kind == ci.CursorKind.CONSTRUCTOR
                                   else '')))
            walk(c)

    walk(function)
    return found


def judge(marked, bodies, overrides):
    problems = []
    for usr, body_marked, name, at, calls in bodies:
        if not (body_marked or usr in marked):
            continue
        for kind, call_at, callee_usr, template_usr, info in calls:
            if kind != 'call':
                problems.append(f'{call_at}: `{name}` is real-time but has a `{kind}` expression')
                continue
            callee_name, callee_in_project, callee_at, made_type = info
            if callee_in_project:
                if callee_usr not in marked and template_usr not in marked:
                    problems.append(f'{call_at}: `{name}` is real-time but calls `{callee_name}` '
                                    f'({callee_at}), which is not marked HAPTICCTRL_RT')
            elif FORBIDDEN.match(callee_name):
                problems.append(f'{call_at}: `{name}` is real-time but calls `{callee_name}`')
            elif re.search(r'Eigen::Matrix<[^>]*-1', made_type or ''):
                problems.append(f'{call_at}: `{name}` is real-time but makes the dynamic-size '
                                f'`{made_type}`')
    for usr, base_usr, name, base_name, at in overrides:
        if base_usr in marked and usr not in marked:
            problems.append(f'{at}: `{name}` overrides the real-time `{base_name}` but is not '
                            f'marked HAPTICCTRL_RT')
    return sorted(set(problems))


def check(jobs):
    marked, bodies, overrides, problems = set(), [], [], []
    with ProcessPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        for m, b, o, p in pool.map(read_unit, jobs):
            marked |= m
            bodies += b
            overrides += o
            problems += p
    return marked, bodies, problems + judge(marked, bodies, overrides)


def main(argv):
    build, root = 'build', '.'
    rest = list(argv)
    if rest[:1] == ['--self-test']:
        return self_test()
    if rest[:1] == ['--build']:
        build = rest[1]
        rest = rest[2:]
    if rest:
        root = rest[0]
    root = os.path.realpath(root)
    database = os.path.join(build if os.path.isabs(build) else os.path.join(root, build),
                            'compile_commands.json')
    with open(database, encoding='utf-8') as f:
        entries = json.load(f)
    jobs, units = [], set()
    for e in entries:
        path = os.path.realpath(os.path.join(e['directory'], e['file']))
        if os.path.relpath(path, root).startswith(ROOMS) and path not in units:
            units.add(path)
            jobs.append((path, arguments(e), root))
    marked, bodies, problems = check(jobs)
    checked = sum(1 for usr, m, *_ in bodies if m or usr in marked)
    for p in problems:
        print(p)
    if problems:
        print(f'check_realtime: {len(problems)} violation(s) of the real-time contract')
        return 1
    print(f'check_realtime: {len(marked)} marked functions, {checked} bodies checked in '
          f'{len(jobs)} units: every call keeps the contract')
    return 0


PLANTED = r'''
#include <string>
#include <vector>
#define HAPTICCTRL_RT [[clang::annotate("hapticctrl::rt")]]
int unmarked_helper(int x);
HAPTICCTRL_RT int marked_helper(int x) { return x + 1; }
struct Base { HAPTICCTRL_RT virtual int step() noexcept { return 0; } virtual ~Base() = default; };
struct Derived : Base { int step() noexcept override { return 1; } };
template <typename T> HAPTICCTRL_RT T twice(T v) { return v + v; }
template <typename T> T thrice(T v) { return v + v + v; }
struct Plain { double x[3]; };
HAPTICCTRL_RT int cycle(std::vector<int>& v) noexcept {
  Plain copy{};                          // fine: made by the compiler
  Plain other = copy;                    // fine
  other = copy;                          // fine
  int a = marked_helper(1) + twice(2) + static_cast<int>(other.x[0]);   // fine
  a += unmarked_helper(a);               // PLANT: unmarked call
  a += thrice(3);                        // PLANT: unmarked template
  v.push_back(a);                        // PLANT: growing container
  std::string text = "x";                // PLANT: a string made
  (void)text.size();                     // fine
  int* p = new int(a);                   // PLANT: new
  auto l = [&] { return std::to_string(a).size(); };  // PLANT: allocation inside a lambda
  return a + *p + static_cast<int>(l());
}
'''


def self_test():
    with tempfile.TemporaryDirectory() as root:
        path = os.path.join(root, 'planted.cpp')
        with open(path, 'w', encoding='utf-8') as f:
            f.write(PLANTED)
        marked, bodies, problems = check([(path, ['-std=c++20', '-xc++'], os.path.realpath(root))])
    expected = ['calls `unmarked_helper`', 'calls `thrice`', 'push_back', 'basic_string::basic_string',
                '`new` expression',
                'to_string', '`Derived::step` overrides']
    # Each planted one found, and nothing else (the lines marked fine are not flagged).
    missing = [e for e in expected if not any(e in p for p in problems)]
    for p in problems:
        print('found:', p)
    if missing or len(problems) != len(expected):
        print(f'check_realtime self-test: missed {missing}, '
              f'{len(problems)} found for {len(expected)} planted')
        return 1
    print(f'check_realtime self-test: all {len(expected)} planted violations found')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
