def divide(a, b):
    return a / b


def main():
    print("crasher: about to divide", flush=True)
    divide(1, 0)
