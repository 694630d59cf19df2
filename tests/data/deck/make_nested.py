#!/usr/bin/python3
"""Generates the 30-file INCLUDE-nested, mixed-format test deck in tests/data/deck/nested.

Run once from that folder; the output is committed as a fixture. Small, large and free
field cards, lower case, tabs, trailing comments, CRLF files, INCLUDEs split over lines,
nesting up to several levels, unsupported cards (FORCE) kept verbatim."""
import random, os
random.seed(7)
def small(name, fields):
    out=[]; line=name.ljust(8)
    for i,f in enumerate(fields):
        if i and i%8==0:
            out.append(line.rstrip()); line='+'.ljust(8)
        line += str(f).ljust(8)
    out.append(line.rstrip())
    return '\n'.join(out)
def large(name, fields):
    out=[]; line=(name+'*').ljust(8)
    for i,f in enumerate(fields):
        if i and i%4==0:
            out.append(line.rstrip()); line='*'.ljust(8)
        line += str(f).rjust(16)
    out.append(line.rstrip())
    return '\n'.join(out)
def free(name, fields):
    rows=[fields[i:i+8] for i in range(0,len(fields),8)] or [[]]
    out=[name+','+','.join(map(str,rows[0]))]
    for r in rows[1:]: out.append('+,'+','.join(map(str,r)))
    return '\n'.join(out)
fmts=[small,large,free]
gid=[1]; eid=[1]; pid=[100]
def grid():
    g=gid[0]; gid[0]+=1
    return ['GRID',[g,'',f"{random.uniform(-5,5):.3f}",f"{random.uniform(-5,5):.4f}",f"{random.uniform(0,3):.2f}"]]
def crod():
    e=eid[0]; eid[0]+=1
    return ['CROD',[e,1,1,2]]
def pbar():
    p=pid[0]; pid[0]+=1
    return ['PBAR',[p,1,'1.-4','2.5-8','2.5-8','5.-8','.1','','.01','.01','-.01','.01','','','','','.85','.85']]
def unknown():
    return ['FORCE',[1,1,0,'10.','1.','0.','0.']]
nfiles=30
children={i:[] for i in range(nfiles)}
for i in range(1,nfiles):
    children[random.randint(max(0,i-6),i-1)].append(i)
def fname(i):
    if i==0: return 'main.bdf'
    d = ['', 'props/', 'mesh/', 'mesh/sub/'][i%4]
    return f"{d}part{i:02d}.{['bdf','dat','inc'][i%3]}"
def rel(frm, to):
    return os.path.relpath(fname(to), os.path.dirname(fname(frm)) or '.')
for i in range(nfiles):
    lines=[]
    if i==0:
        lines += ['ID NESTED,TEST','SOL 103','TIME 10','CEND','TITLE = THIRTY FILE NESTED DECK','SUBCASE 1','  METHOD = 1','  SPC = 1','BEGIN BULK',
                  small('GRID',[1,'','0.','0.','0.']), small('GRID',[2,'','1.','0.','0.']),
                  small('MAT1',[1,'2.1+11','','.3','7800.']), small('PROD',[1,1,'1.-4'])]
        gid[0]=3
    lines.append(f"$ file {i}: {fname(i)} ----------------------------------")
    kids=list(children[i])
    for k in range(random.randint(4,12)):
        name,fields=random.choice([grid,grid,crod,pbar,unknown])()
        f=random.choice(fmts)
        txt=f(name,fields)
        if random.random()<0.15: txt=txt.lower()
        if random.random()<0.2 and f is small and len(name)<8: txt=txt.replace(name.ljust(8),name+'\t',1)
        if random.random()<0.2: txt=txt+'  $ trailing note'
        lines.append(txt)
        if kids and random.random()<0.4:
            c=kids.pop(0); r=rel(i,c)
            if random.random()<0.3 and '/' in r:
                a,b=r.split('/',1); lines.append(f"INCLUDE '{a}/\n   {b}'")
            else:
                lines.append(f"include '{r}'")
    for c in kids: lines.append(f"INCLUDE '{rel(i,c)}'")
    if i==0: lines += ['ENDDATA','$ trailing text after ENDDATA']
    nl = '\r\n' if i%7==3 else '\n'
    text=nl.join('\n'.join(lines).split('\n'))+nl
    os.makedirs(os.path.dirname(fname(i)) or '.', exist_ok=True)
    open(fname(i),'w',newline='').write(text)
