def load(path): raise NotImplementedError
def save(ma, path): raise NotImplementedError
