"""Counts the members of the C++ classes in a source file: data members (each declarator of a
declaration) and member functions (constructors and operators included; nested types are
classes of their own and count as none). Comments, literals and preprocessor lines are dropped
first. It reads the code the project writes (clang-format's layout), not all of C++: the layout
test (layout_test.py) and its own test hold it to known counts."""
import re

# A class or struct definition's head up to its opening brace.
_HEAD = re.compile(r'\b(class|struct|union)\s+(?:alignas\([^)]*\)\s*)?(\w+)\s*(?:final\s*)?'
                   r'(?::[^;{()]*)?\{')
_SKIPPED = re.compile(r'^(using|friend|static_assert|typedef)\b')
_ACCESS = re.compile(r'^\s*(public|private|protected)\s*:(?!:)')


def strip(text):
    """The code less comments, string and character literals and preprocessor lines."""
    text = re.sub(r'/\*.*?\*/', lambda m: '\n' * m.group(0).count('\n'), text, flags=re.S)
    text = re.sub(r'//[^\n]*', '', text)
    text = re.sub(r'"(\\.|[^"\\\n])*"', '""', text)
    text = re.sub(r"'(\\.|[^'\\\n])*'", "''", text)
    return re.sub(r'^\s*#[^\n]*', '', text, flags=re.M)


def _closing(text, i):
    """The index of the brace that closes the one at text[i]."""
    depth = 0
    for j in range(i, len(text)):
        if text[j] == '{':
            depth += 1
        elif text[j] == '}':
            depth -= 1
            if depth == 0:
                return j
    return len(text)


def _top_level(s):
    """(character, index) of s outside (), [], {} and template arguments <...>."""
    depth, prev = 0, ''
    for k, c in enumerate(s):
        if c in '([{':
            if depth == 0:
                yield c, k
            depth += 1
        elif c in ')]}':
            depth -= 1
        elif c == '<' and (prev.isalnum() or prev == '_') and s[k + 1:k + 2] != '<':
            depth += 1
        elif c == '>' and depth > 0 and s[k - 1:k] != '-':
            depth -= 1
        elif depth == 0:
            yield c, k
        if not c.isspace():
            prev = c


def _declares_function(s):
    """Whether a declaration (less any template prefix) declares a function: a top-level '('
    before any top-level '=' or '{' (an operator's name may hold '=')."""
    s = re.sub(r'^template\s*<[^;{]*?>\s*(?=[A-Za-z_])', '', s.strip())
    if re.search(r'\boperator\b', s.split('=')[0] if 'operator' not in s else s):
        return True
    for c, _ in _top_level(s):
        if c == '(':
            return True
        if c in '={':
            return False
    return False


def _declarators(s):
    return 1 + sum(1 for c, _ in _top_level(s) if c == ',')


def members(body):
    """(data members, member functions) at the top level of a class body."""
    data = functions = 0
    i, statement = 0, ''
    while i < len(body):
        c = body[i]
        if c == ':' and _ACCESS.fullmatch(statement + c):
            statement, i = '', i + 1
            continue
        if c == '{':
            head = statement.strip()
            end = _closing(body, i)
            if re.search(r'\b(enum|class|struct|union)\b[^()]*$', head):
                # A nested type: its body is a class of its own; a declarator may follow.
                semicolon = body.find(';', end)
                declarator = body[end + 1:semicolon].strip()
                data += _declarators(declarator) if declarator else 0
                statement, i = '', semicolon + 1
                continue
            in_initializers = re.search(r'\)\s*(noexcept\s*)?:[^:]', head) and re.search(
                r'[\w>]\s*$', head)
            if _declares_function(head) and not in_initializers:
                functions += 1
                statement, i = '', end + 1
                continue
            statement += body[i:end + 1]  # a member's brace initializer, or a constructor's
            i = end + 1
            continue
        if c == ';':
            s = statement.strip()
            statement, i = '', i + 1
            if not s or _SKIPPED.match(s) or re.match(r'^template\s*<.*>\s*(friend|using)\b', s):
                continue
            if _declares_function(s):
                functions += 1
            else:
                data += _declarators(s)
            continue
        statement += c
        i += 1
    return data, functions


def classes(text):
    """(name, data members, member functions) of each class or struct defined in `text`."""
    text = strip(text)
    for m in _HEAD.finditer(text):
        if re.search(r'\benum\s+$', text[max(0, m.start() - 12):m.start()]):
            continue
        start = m.end() - 1
        data, functions = members(text[start + 1:_closing(text, start)])
        yield m.group(2), data, functions
