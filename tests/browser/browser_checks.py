"""What the browser tests share: one list of failed checks, which check() adds to and each test
reads at its end (a test that imports another's helpers shares the list with it)."""

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message)
